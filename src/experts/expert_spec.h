// Which experts to train: the paper's walker grid (appendix "Walker"), smaller ones, and grids
// on any other registered task (the humanoid's, whose reward ignores its style label).
//
// An expert is trained on a task of the registry (env/registry.h) for one context value (the
// walker's target speed, the humanoid's style label), or for a group of them that it takes as
// a condition input: the value itself ("value": observation ++ [target_speed]) or a one-hot of
// its position in the group ("one_hot": observation ++ [0, 1, 0, ...], for unordered styles).
// Each group is crossed with initial policy log-std values and seeds, so the set is diverse in
// movement style.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vaegail {

struct ExpertSpec {
  std::string id;
  std::vector<double> targets;  // one: single-context expert; several: context-conditioned
  double init_log_std = -1.0;
  std::uint64_t seed = 0;
  std::string task = "walker";
  std::string condition = "value";  // or "one_hot"
  bool conditioned() const { return targets.size() > 1; }
  int condition_dim() const;
  // The policy's condition input for an episode at `target` (empty for a single-context expert).
  std::vector<float> condition_for(double target) const;
};

struct ExpertGrid {
  std::vector<std::vector<double>> groups;
  std::vector<double> init_log_stds;
  int seeds = 1;
  int first_seed = 0;  // seeds first_seed .. first_seed + seeds - 1: a later grid adds experts to an earlier one
  std::string task = "walker";
  std::string condition = "value";
};

// The paper: {-1}, {0}, {1}, {3}, {-1, 0, 1}, {-1, 0, 3} x log-std {0, -1, -2, -3} x 3 seeds.
ExpertGrid paper_walker_grid();
// One seed and log-std -1 and -2 per group: 12 experts.
ExpertGrid small_walker_grid();
// Ids are the group, log-std and seed (speed1_logstd-1_seed0, ctx-1_0_1_logstd0_seed2), after
// the task's name for tasks other than the walker (humanoid_ctx0_1_2_logstd-1_seed0).
std::vector<ExpertSpec> expand(const ExpertGrid& grid);

void to_json(nlohmann::json& j, const ExpertSpec& s);
void from_json(const nlohmann::json& j, ExpertSpec& s);
void to_json(nlohmann::json& j, const ExpertGrid& g);
void from_json(const nlohmann::json& j, ExpertGrid& g);

}  // namespace vaegail
