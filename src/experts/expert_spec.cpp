#include "experts/expert_spec.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

namespace vaegail {

ExpertGrid paper_walker_grid() {
  return {{{-1}, {0}, {1}, {3}, {-1, 0, 1}, {-1, 0, 3}}, {0, -1, -2, -3}, 3};
}

ExpertGrid small_walker_grid() { return {{{-1}, {0}, {1}, {3}, {-1, 0, 1}, {-1, 0, 3}}, {-1, -2}, 1}; }

namespace {
std::string group_name(const std::vector<double>& targets) {
  std::string name = targets.size() > 1 ? "ctx" : "speed";
  for (size_t i = 0; i < targets.size(); ++i) name += fmt::format("{}{:g}", i ? "_" : "", targets[i]);
  return name;
}

void check_condition(const std::string& condition) {
  if (condition != "value" && condition != "one_hot")
    throw std::invalid_argument("expert condition is value or one_hot, not '" + condition + "'");
}
}  // namespace

int ExpertSpec::condition_dim() const {
  if (!conditioned()) return 0;
  return condition == "one_hot" ? static_cast<int>(targets.size()) : 1;
}

std::vector<float> ExpertSpec::condition_for(double target) const {
  if (!conditioned()) return {};
  if (condition != "one_hot") return {static_cast<float>(target)};
  const auto at = std::find(targets.begin(), targets.end(), target);
  if (at == targets.end()) throw std::invalid_argument(id + ": " + std::to_string(target) + " is not one of its targets");
  std::vector<float> one_hot(targets.size(), 0.f);
  one_hot[at - targets.begin()] = 1.f;
  return one_hot;
}

std::vector<ExpertSpec> expand(const ExpertGrid& grid) {
  check_condition(grid.condition);
  const std::string prefix = grid.task == "walker" ? "" : grid.task + "_";
  std::vector<ExpertSpec> specs;
  for (const auto& group : grid.groups)
    for (double log_std : grid.init_log_stds)
      for (int seed = grid.first_seed; seed < grid.first_seed + grid.seeds; ++seed) {
        ExpertSpec s;
        s.targets = group;
        s.init_log_std = log_std;
        s.seed = static_cast<std::uint64_t>(seed);
        s.task = grid.task;
        s.condition = grid.condition;
        s.id = prefix + group_name(group) + fmt::format("_logstd{:g}_seed{}", log_std, seed);
        specs.push_back(s);
      }
  return specs;
}

void to_json(nlohmann::json& j, const ExpertSpec& s) {
  j = {{"id", s.id}, {"targets", s.targets}, {"init_log_std", s.init_log_std}, {"seed", s.seed},
       {"task", s.task}, {"condition", s.condition}};
}

void from_json(const nlohmann::json& j, ExpertSpec& s) {
  j.at("id").get_to(s.id);
  j.at("targets").get_to(s.targets);
  j.at("init_log_std").get_to(s.init_log_std);
  j.at("seed").get_to(s.seed);
  // Runs that predate other tasks are the walker's, conditioned on the value.
  s.task = j.value("task", std::string("walker"));
  s.condition = j.value("condition", std::string("value"));
  check_condition(s.condition);
}

void to_json(nlohmann::json& j, const ExpertGrid& g) {
  j = {{"groups", g.groups}, {"init_log_stds", g.init_log_stds}, {"seeds", g.seeds}, {"first_seed", g.first_seed},
       {"task", g.task}, {"condition", g.condition}};
}

void from_json(const nlohmann::json& j, ExpertGrid& g) {
  j.at("groups").get_to(g.groups);
  j.at("init_log_stds").get_to(g.init_log_stds);
  j.at("seeds").get_to(g.seeds);
  g.first_seed = j.value("first_seed", 0);
  g.task = j.value("task", std::string("walker"));
  g.condition = j.value("condition", std::string("value"));
  check_condition(g.condition);
  if (g.seeds < 1 || g.first_seed < 0) throw std::invalid_argument("grid: seeds must be >= 1 and first_seed >= 0");
}

}  // namespace vaegail
