#include "experts/expert_spec.h"

#include <cstdio>
#include <stdexcept>

namespace vaegail {

ExpertGrid paper_walker_grid() {
  return {{{-1}, {0}, {1}, {3}, {-1, 0, 1}, {-1, 0, 3}}, {0, -1, -2, -3}, 3};
}

ExpertGrid small_walker_grid() { return {{{-1}, {0}, {1}, {3}, {-1, 0, 1}, {-1, 0, 3}}, {-1, -2}, 1}; }

namespace {
std::string group_name(const std::vector<double>& targets) {
  std::string name = targets.size() > 1 ? "ctx" : "speed";
  char buf[16];
  for (size_t i = 0; i < targets.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%g", i ? "_" : "", targets[i]);
    name += buf;
  }
  return name;
}
}  // namespace

std::vector<ExpertSpec> expand(const ExpertGrid& grid) {
  std::vector<ExpertSpec> specs;
  for (const auto& group : grid.groups)
    for (double log_std : grid.init_log_stds)
      for (int seed = grid.first_seed; seed < grid.first_seed + grid.seeds; ++seed) {
        ExpertSpec s;
        s.targets = group;
        s.init_log_std = log_std;
        s.seed = static_cast<std::uint64_t>(seed);
        char buf[64];
        std::snprintf(buf, sizeof buf, "_logstd%g_seed%d", log_std, seed);
        s.id = group_name(group) + buf;
        specs.push_back(s);
      }
  return specs;
}

void to_json(nlohmann::json& j, const ExpertSpec& s) {
  j = {{"id", s.id}, {"targets", s.targets}, {"init_log_std", s.init_log_std}, {"seed", s.seed}};
}

void from_json(const nlohmann::json& j, ExpertSpec& s) {
  j.at("id").get_to(s.id);
  j.at("targets").get_to(s.targets);
  j.at("init_log_std").get_to(s.init_log_std);
  j.at("seed").get_to(s.seed);
}

void to_json(nlohmann::json& j, const ExpertGrid& g) {
  j = {{"groups", g.groups}, {"init_log_stds", g.init_log_stds}, {"seeds", g.seeds}, {"first_seed", g.first_seed}};
}

void from_json(const nlohmann::json& j, ExpertGrid& g) {
  j.at("groups").get_to(g.groups);
  j.at("init_log_stds").get_to(g.init_log_stds);
  j.at("seeds").get_to(g.seeds);
  g.first_seed = j.value("first_seed", 0);
  if (g.seeds < 1 || g.first_seed < 0) throw std::invalid_argument("grid: seeds must be >= 1 and first_seed >= 0");
}

}  // namespace vaegail
