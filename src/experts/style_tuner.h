// `vaegail experts tune STYLE.json`: CMA-ES (experts/parameter_tuner.h) over some of a humanoid
// gait style's parameters (experts/gait_parameters.h), scored over simulated episodes from
// perturbed starts with random pushes. The style file says what to tune and what the style
// must look like; the result is written back as its "parameters".
//
// A style file (configs/humanoid_styles/{train,eval}/NAME.json):
//   {
//     "style": "walk", "set": "train", "description": "what a person sees",
//     "parameters": { GaitParameters, keys left out at their defaults },
//     "targets": { "MEASURE": [target, tolerance], ... },   measures: kStyleMeasures
//     "tune": {
//       "start": "walk.json",            optional: the style file (relative to this one) whose parameters
//                                         a fresh search starts from, this file's "parameters" set over
//                                         them; without it, this file's over GaitParameters' defaults
//       "parameters": { "NAME": [low, high], ... },   the tuned GaitParameters and their bounds
//       "generations": 40, "population": 0, "sigma": 0.2, "seed": 0,
//       "episodes": 5, "pushes": 1, "push_force": 200
//     },
//     "tuned": { written by the tuner: cost, generations, the command }
//   }
//
// The cost of a candidate is the mean over the episodes of
//   kFallWeight (1 - time_up / duration)                          staying up first
//   + sum over targets of huber((measure - target) / tolerance)   the style
//   + (heading_error / kHeadingTolerance)^2 + (lateral_drift / kDriftTolerance)^2   going where told
//   + kEffortWeight effort
// huber(m) = m^2 up to |m| = kHuberKnee, then linear in |m| with the same slope there: a far miss
// still tells the search which way is better (a capped square is flat far away, and a search that
// starts many tolerances off its targets, as a new style does, then sees no difference between
// its candidates; the first tuning of the simple walk stalled so for 16 generations). An episode
// that falls within kMeasuredAfter seconds has no gait to measure and pays huber(kUnmeasuredMiss)
// per target. Without its targets a re-tune drifts back to the walk it started from (the
// prototype's lesson), so every style states its signature as targets.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>

#include "experts/gait_episode.h"
#include "experts/parameter_tuner.h"

namespace vaegail {

// The measures a style's targets may name, from a GaitEpisodeResult.
//   speed, cadence (steps/min), step_length, step_width, pelvis_height   GaitEpisodeResult's
//   sway_speed, turn_rate, root_height, head_forward, hand_height, hand_spread, foot_spread
//                                                                       its mean style measures
//   arm_swing                                                           its gait signature's
inline constexpr std::array<const char*, 13> kStyleMeasures = {
    "speed",        "cadence",     "step_length",  "step_width",  "pelvis_height", "sway_speed", "turn_rate",
    "root_height", "head_forward", "hand_height", "hand_spread", "foot_spread",   "arm_swing"};
// The measure `name` of an episode; throws std::invalid_argument for a name not in kStyleMeasures.
double style_measure(const GaitEpisodeResult& episode, const std::string& name);

struct StyleTarget {
  std::string measure;
  double target = 0, tolerance = 1;
};

struct StyleTuning {
  std::vector<StyleTarget> targets;
  std::vector<TunedParameter> tuned;
  TuneOptions options;
  nlohmann::json start;  // the parameters a fresh search starts from (every one of them, as JSON)
  int episodes = 5;
  GaitEpisodeOptions episode;  // pushes and their force (seed set per episode)
};

inline constexpr double kFallWeight = 200, kHuberKnee = 3, kUnmeasuredMiss = 10, kMeasuredAfter = 2.0;
inline constexpr double kHeadingTolerance = 0.2, kDriftTolerance = 1.0, kEffortWeight = 1.0;

// Reads a style file's targets and "tune" section. Throws one line naming the file and the key
// when one is missing or malformed (a target's measure unknown, a tolerance not > 0, a tuned
// parameter that GaitParameters lacks).
StyleTuning read_style_tuning(const std::string& style_path);

// The style term of a miss of `tolerances` tolerances (the formula above).
double style_miss_cost(double tolerances);
// The cost of one episode (the formula above) for `duration` seconds of episode.
double style_episode_cost(const GaitEpisodeResult& episode, const std::vector<StyleTarget>& targets, double duration);

// The cost of parameters: the mean episode cost over tuning.episodes episodes, episode e reset
// with derive_seed(tuning.options.seed, e) on a fresh humanoid environment.
double style_cost(const StyleTuning& tuning, const GaitParameters& parameters);

// Tunes the style of `style_path` (its search state and metrics.csv in `run_dir`, which a rerun
// of the same command resumes from, and which a second process is refused, util/run_lock.h) on `jobs` threads, then writes the best parameters into the
// style file (atomically; every other key kept) with a "tuned" record naming `command`.
TuneResult tune_style(const std::string& style_path, const std::string& run_dir, int jobs, const std::string& command);

}  // namespace vaegail
