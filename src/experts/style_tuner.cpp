#include "experts/style_tuner.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "env/humanoid.h"
#include "util/atomic_file.h"
#include "util/json_file.h"
#include "util/run_lock.h"
#include "util/rng.h"

namespace vaegail {
namespace {

// A [low, high] or [target, tolerance] pair under `key`, one line naming the file otherwise.
std::pair<double, double> read_pair(const nlohmann::json& value, const std::string& where, const std::string& key) {
  if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number())
    throw std::invalid_argument(where + ": '" + key + "' must be a pair of numbers");
  return {value[0].get<double>(), value[1].get<double>()};
}

const nlohmann::json& required(const nlohmann::json& object, const std::string& where, const char* key) {
  if (!object.contains(key)) throw std::invalid_argument(where + ": no '" + key + "'");
  return object.at(key);
}

}  // namespace

double style_measure(const GaitEpisodeResult& e, const std::string& name) {
  if (name == "speed") return e.speed;
  if (name == "cadence") return e.cadence;
  if (name == "step_length") return e.step_length;
  if (name == "step_width") return e.step_width;
  if (name == "pelvis_height") return e.pelvis_height;
  if (name == "sway_speed") return e.style[kSwaySpeed];
  if (name == "turn_rate") return e.style[kTurnRate];
  if (name == "root_height") return e.style[kRootHeight];
  if (name == "head_forward") return e.style[kHeadForward];
  if (name == "hand_height") return e.style[kHandHeight];
  if (name == "hand_spread") return e.style[kHandSpread];
  if (name == "foot_spread") return e.style[kFootSpread];
  if (name == "arm_swing") return e.signature[7];
  throw std::invalid_argument("'" + name + "' is not a style measure");
}

StyleTuning read_style_tuning(const std::string& path) {
  const nlohmann::json style = read_json_file(path);
  StyleTuning t;
  for (const auto& [measure, pair] : required(style, path, "targets").items()) {
    if (std::find(kStyleMeasures.begin(), kStyleMeasures.end(), measure) == kStyleMeasures.end())
      throw std::invalid_argument(path + ": target '" + measure + "' is not a style measure");
    const auto [target, tolerance] = read_pair(pair, path, "targets." + measure);
    if (!(tolerance > 0)) throw std::invalid_argument(path + ": target '" + measure + "' needs a tolerance > 0");
    t.targets.push_back({measure, target, tolerance});
  }
  const nlohmann::json& tune = required(style, path, "tune");
  const nlohmann::json known = GaitParameters{};
  for (const auto& [name, bounds] : required(tune, path, "parameters").items()) {
    if (!known.contains(name)) throw std::invalid_argument(path + ": tuned '" + name + "' is not a gait parameter");
    const auto [low, high] = read_pair(bounds, path, "tune.parameters." + name);
    t.tuned.push_back({name, low, high});
  }
  try {
    t.options.generations = tune.value("generations", t.options.generations);
    t.options.population = tune.value("population", t.options.population);
    t.options.sigma = tune.value("sigma", t.options.sigma);
    t.options.seed = tune.value("seed", t.options.seed);
    t.episodes = tune.value("episodes", t.episodes);
    t.episode.pushes = tune.value("pushes", 1);
    t.episode.push_force = tune.value("push_force", t.episode.push_force);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(path + ": malformed 'tune': " + first_line(e.what()));
  }
  if (t.episodes < 1 || t.options.generations < 0)
    throw std::invalid_argument(path + ": 'tune' needs episodes >= 1 and generations >= 0");
  // The style's own parameters over its starting point's: a style fixes its knobs (an arm pose,
  // a back lean) and takes the rest from the style it is tuned from.
  nlohmann::json start = nlohmann::json(GaitParameters{});
  if (tune.contains("start"))
    start = read_gait_style((std::filesystem::path(path).parent_path() / tune.at("start").get<std::string>()).string());
  for (const auto& [name, value] : required(style, path, "parameters").items()) start[name] = value;
  t.start = nlohmann::json(gait_parameters_from_json(start, path));
  return t;
}

double style_miss_cost(double tolerances) {
  const double m = std::abs(tolerances);
  return m <= kHuberKnee ? m * m : kHuberKnee * (2 * m - kHuberKnee);
}

double style_episode_cost(const GaitEpisodeResult& episode, const std::vector<StyleTarget>& targets, double duration) {
  double cost = kFallWeight * (1 - std::min(episode.time_up / duration, 1.0));
  const bool measured = episode.time_up >= kMeasuredAfter;
  for (const auto& t : targets) {
    const double miss = measured ? (style_measure(episode, t.measure) - t.target) / t.tolerance : kUnmeasuredMiss;
    cost += style_miss_cost(std::isfinite(miss) ? miss : kUnmeasuredMiss);
  }
  const double heading = episode.heading_error / kHeadingTolerance, drift = episode.lateral_drift / kDriftTolerance;
  return cost + heading * heading + drift * drift + kEffortWeight * episode.effort;
}

double style_cost(const StyleTuning& tuning, const GaitParameters& parameters) {
  // One environment per thread: the tuner scores candidates on several at once.
  thread_local std::unique_ptr<HumanoidEnv> env;
  if (!env) env = std::make_unique<HumanoidEnv>();
  const double duration = (tuning.episode.steps > 0 ? tuning.episode.steps : env->episode_length()) * env->control_timestep();
  double total = 0;
  for (int e = 0; e < tuning.episodes; ++e) {
    GaitEpisodeOptions options = tuning.episode;
    options.seed = derive_seed(tuning.options.seed, static_cast<std::uint64_t>(e));
    total += style_episode_cost(run_gait_episode(*env, parameters, options), tuning.targets, duration);
  }
  return total / tuning.episodes;
}

TuneResult tune_style(const std::string& style_path, const std::string& run_dir, int jobs, const std::string& command) {
  StyleTuning tuning = read_style_tuning(style_path);
  tuning.options.jobs = jobs;
  const RunLock lock = lock_run_directory(run_dir);  // one search per run directory (creates it)
  const auto cost = [&](const nlohmann::json& parameters, int) {
    return style_cost(tuning, gait_parameters_from_json(parameters, style_path));
  };
  const TuneResult result = tune_parameters(tuning.start, tuning.tuned, tuning.options, cost, run_dir + "/state.json",
                                            run_dir + "/metrics.csv");
  nlohmann::json style = read_json_file(style_path);
  style["parameters"] = result.parameters;
  style["tuned"] = {{"cost", result.cost}, {"generations", result.generations}, {"command", command}};
  write_file_atomically(style_path, style.dump(2) + "\n");
  return result;
}

}  // namespace vaegail
