// Which experts to train: the paper's walker grid (appendix "Walker") and smaller ones.
//
// An expert is trained for one target speed, or for a group of target speeds that it takes as
// a context input (then its policy input is observation ++ [target_speed]). Each group is
// crossed with initial policy log-std values and seeds, so the set is diverse in movement style.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace vaegail {

struct ExpertSpec {
  std::string id;
  std::vector<double> targets;  // one: single-speed expert; several: context-conditioned
  double init_log_std = -1.0;
  std::uint64_t seed = 0;
  bool conditioned() const { return targets.size() > 1; }
  int condition_dim() const { return conditioned() ? 1 : 0; }
};

struct ExpertGrid {
  std::vector<std::vector<double>> groups;
  std::vector<double> init_log_stds;
  int seeds = 1;
  int first_seed = 0;  // seeds first_seed .. first_seed + seeds - 1: a later grid adds experts to an earlier one
};

// The paper: {-1}, {0}, {1}, {3}, {-1, 0, 1}, {-1, 0, 3} x log-std {0, -1, -2, -3} x 3 seeds.
ExpertGrid paper_walker_grid();
// One seed and log-std -1 and -2 per group: 12 experts.
ExpertGrid small_walker_grid();
std::vector<ExpertSpec> expand(const ExpertGrid& grid);

void to_json(nlohmann::json& j, const ExpertSpec& s);
void from_json(const nlohmann::json& j, ExpertSpec& s);
void to_json(nlohmann::json& j, const ExpertGrid& g);
void from_json(const nlohmann::json& j, ExpertGrid& g);

}  // namespace vaegail
