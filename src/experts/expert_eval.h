// `vaegail experts eval`: does an expert move at its target speeds without falling?
// Mean achieved speed per target over episodes (each episode's mean centre-of-mass speed),
// its distance to the target speed, and the share of episodes that end in a fall. A humanoid
// expert is refused: its context is a style label, no speed, and the humanoid's demonstrators are
// gait controllers, graded by `experts eval --task humanoid --styles` (experts/gait_eval.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "experts/expert_trainer.h"

namespace vaegail {

struct TargetResult {
  double target = 0;        // the context: a target speed
  std::string label;        // the target as printed: "1.00"
  double target_speed = 0;  // the target (m/s), under its own name in the JSON report
  int episodes = 0;
  double mean_speed = 0;
  double speed_error = 0;  // |mean_speed - target_speed|
  double fall_rate = 0;
};

struct ExpertEvaluation {
  std::string id;
  std::vector<TargetResult> targets;
  // The bar for the published set: every target within max_error m/s, falls below max_fall_rate.
  bool passes(double max_error = 0.3, double max_fall_rate = 0.1) const;
};

struct ExpertEvalOptions {
  int episodes_per_target = 10;
  bool stochastic = false;  // mean actions by default
  std::uint64_t seed = 12345;
  int num_envs = 10;
  int threads = 1;
};

ExpertEvaluation evaluate_expert(const LoadedExpert& expert, const ExpertEvalOptions& options);
std::string format_evaluations(const std::vector<ExpertEvaluation>& evaluations);

}  // namespace vaegail
