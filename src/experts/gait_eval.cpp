#include "experts/gait_eval.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "util/rng.h"

namespace vaegail {

GaitStyleEvaluation evaluate_gait_style(const std::string& name, const GaitParameters& parameters,
                                        const GaitEvalOptions& options, const std::function<void()>& episode_done) {
  HumanoidEnv env;
  GaitStyleEvaluation e;
  e.name = name;
  e.parameters = parameters;
  e.episodes = options.episodes;
  double steps = 0, seconds = 0;
  std::vector<int> replays;
  for (int i = 0; i < options.episodes; ++i) {
    GaitEpisodeOptions o = options.episode;
    o.seed = derive_seed(options.seed, static_cast<std::uint64_t>(i));
    const int pushes = o.pushes;
    o.pushes = 0;
    const GaitEpisodeResult calm = run_gait_episode(env, parameters, o);
    o.pushes = pushes;
    const GaitEpisodeResult pushed = run_gait_episode(env, parameters, o);
    e.falls += calm.fallen;
    e.pushed_falls += pushed.fallen;
    steps += calm.control_steps + pushed.control_steps;
    seconds += calm.wall_seconds + pushed.wall_seconds;
    const double w = 1.0 / options.episodes;
    e.time_up += w * calm.time_up;
    e.speed += w * calm.speed;
    e.step_length += w * calm.step_length;
    e.cadence += w * calm.cadence;
    e.step_width += w * calm.step_width;
    e.pelvis_height += w * calm.pelvis_height;
    e.lateral_drift += w * std::abs(calm.lateral_drift);
    e.heading_error += w * calm.heading_error;
    e.effort += w * calm.effort;
    for (size_t k = 0; k < e.signature.size(); ++k) e.signature[k] += w * calm.signature[k];
    if (options.replay) replays.push_back(held_mean_replay_steps(env, parameters, o));
    if (episode_done) episode_done();
  }
  e.control_steps_per_s = seconds > 0 ? steps / seconds : 0;
  if (!replays.empty()) {
    e.replay_min = *std::min_element(replays.begin(), replays.end());
    e.replay_max = *std::max_element(replays.begin(), replays.end());
    for (int r : replays) e.replay_mean += static_cast<double>(r) / replays.size();
  }
  return e;
}

std::string format_gait_evaluations(const std::vector<GaitStyleEvaluation>& evaluations) {
  std::string out = fmt::format("{:<16} {:>6} {:>8} {:>7} {:>8} {:>8} {:>8} {:>8} {:>7} {:>8} {:>7} {:>10} {:>11}\n",
                                "style", "up", "pushed up", "speed", "step L", "cadence", "step W", "pelvis z", "drift",
                                "|head e|", "effort", "ctrl st/s", "replay");
  for (const auto& e : evaluations) {
    const std::string replay = e.replay_max > 0 ? fmt::format("{:.1f} ({}-{})", e.replay_mean, e.replay_min, e.replay_max) : "-";
    out += fmt::format("{:<16} {:>6} {:>8} {:7.3f} {:8.3f} {:8.1f} {:8.3f} {:8.3f} {:7.2f} {:8.3f} {:7.3f} {:10.0f} {:>11}\n",
                       e.name, fmt::format("{}/{}", e.episodes - e.falls, e.episodes),
                       fmt::format("{}/{}", e.episodes - e.pushed_falls, e.episodes), e.speed, e.step_length,
                       e.cadence, e.step_width, e.pelvis_height, e.lateral_drift, e.heading_error, e.effort,
                       e.control_steps_per_s, replay);
  }
  out += fmt::format("\n{:<16}", "signature");
  for (const char* statistic : kGaitStatistics) out += fmt::format(" {:>13}", statistic);
  out += "\n";
  for (const auto& e : evaluations) {
    out += fmt::format("{:<16}", e.name);
    for (double x : e.signature) out += fmt::format(" {:13.3f}", x);
    out += "\n";
  }
  out += "\nspeed, step L(ength), cadence (steps/min), step W(idth), pelvis z, |lateral drift|, |heading error| and\n"
         "effort (mean action^2) are means over the episodes without pushes; replay: control steps until the root\n"
         "is 0.1 m off when the recorded mean actions are replayed held (mean, min-max).\n";
  for (const auto& e : evaluations)
    if (e.raw_control_steps_per_s > 0)
      out += fmt::format("{}: {:.0f} control steps/s with the controller, {:.0f} raw mj_step right after: ratio {:.2f}\n",
                         e.name, e.control_steps_per_s, e.raw_control_steps_per_s,
                         e.control_steps_per_s / e.raw_control_steps_per_s);
  return out;
}

std::vector<std::pair<std::string, double>> gait_evaluation_row(const GaitStyleEvaluation& e) {
  std::vector<std::pair<std::string, double>> row = {
      {"episodes", e.episodes},       {"falls", e.falls},
      {"pushed_falls", e.pushed_falls}, {"time_up", e.time_up},
      {"speed", e.speed},             {"step_length", e.step_length},
      {"cadence", e.cadence},         {"step_width", e.step_width},
      {"pelvis_height", e.pelvis_height}, {"lateral_drift", e.lateral_drift},
      {"heading_error", e.heading_error}, {"effort", e.effort},
      {"control_steps_per_s", e.control_steps_per_s}, {"replay_mean", e.replay_mean},
      {"replay_min", e.replay_min},   {"replay_max", e.replay_max}};
  for (size_t k = 0; k < e.signature.size(); ++k)
    row.emplace_back(std::string("signature_") + kGaitStatistics[k], e.signature[k]);
  return row;
}

}  // namespace vaegail
