#include "experts/gait_parameters.h"

#include <stdexcept>

#include "util/json_file.h"

namespace vaegail {

GaitParameters gait_parameters_from_json(const nlohmann::json& parameters, const std::string& where) {
  if (!parameters.is_object()) throw std::invalid_argument(where + ": gait parameters must be a JSON object");
  const nlohmann::json known = GaitParameters{};
  for (const auto& [key, value] : parameters.items()) {
    if (!known.contains(key)) throw std::invalid_argument(where + ": '" + key + "' is not a gait parameter");
    if (!value.is_number()) throw std::invalid_argument(where + ": gait parameter '" + key + "' is not a number");
  }
  const auto p = parameters.get<GaitParameters>();
  auto require = [&](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(where + ": gait parameters need " + what);
  };
  require(p.step_min_time > 0 && p.step_max_time > 0, "step_min_time and step_max_time > 0");
  require(p.wander_period > 0 && p.turn_rate > 0, "wander_period and turn_rate > 0");
  require(p.swing_descent_phase > 0 && p.swing_descent_phase <= 1, "swing_descent_phase in (0, 1]");
  require(p.swing_reach_phase > 0 && p.swing_reach_phase <= 1, "swing_reach_phase in (0, 1]");
  require(p.back_roll_filter > 0 && p.support_ramp > 0, "back_roll_filter and support_ramp > 0");
  return p;
}

GaitParameters read_gait_style(const std::string& path) {
  const nlohmann::json style = read_json_file(path);
  if (!style.is_object() || !style.contains("parameters"))
    throw std::invalid_argument(path + ": a gait style file needs a 'parameters' object");
  return gait_parameters_from_json(style["parameters"], path);
}

}  // namespace vaegail
