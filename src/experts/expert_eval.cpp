#include "experts/expert_eval.h"

#include <cmath>
#include <cstdio>

#include "experts/agent_policy.h"
#include "util/rng.h"

namespace vaegail {

bool ExpertEvaluation::passes(double max_error, double max_fall_rate) const {
  for (const auto& t : targets)
    if (!(t.speed_error <= max_error) || t.fall_rate >= max_fall_rate) return false;
  return !targets.empty();
}

ExpertEvaluation evaluate_expert(const LoadedExpert& expert, const ExpertEvalOptions& o) {
  const auto prototype = make_expert_env(expert.spec);
  ExpertEvaluation result;
  result.id = expert.spec.id;
  for (double target : expert.spec.targets) {
    RecordRequest request;
    std::vector<std::vector<float>> conditions;
    for (int k = 0; k < o.episodes_per_target; ++k) {
      request.seeds.push_back(derive_seed(o.seed, k));
      request.contexts.push_back({target});
      conditions.push_back(expert.spec.condition_for(target));
    }
    request.num_envs = o.num_envs;
    request.num_threads = o.threads;
    const auto episodes = record_episodes(*prototype, request,
                                          agent_batch_policy(expert.agent, conditions, o.stochastic, o.seed));
    TargetResult t;
    t.target = target;
    t.episodes = static_cast<int>(episodes.size());
    for (const auto& e : episodes) {
      t.mean_speed += e.attributes.at("mean_com_speed") / t.episodes;
      t.fall_rate += (e.terminations.back() ? 1.0 : 0.0) / t.episodes;
    }
    t.speed_error = std::abs(t.mean_speed - t.target);
    result.targets.push_back(t);
  }
  return result;
}

std::string format_evaluations(const std::vector<ExpertEvaluation>& evaluations) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-28s %7s %9s %10s %11s %9s  %s\n", "expert", "target", "episodes",
                "mean speed", "|mean-tgt|", "fall rate", "passes");
  out += line;
  int passing = 0;
  for (const auto& e : evaluations) {
    const bool ok = e.passes();
    passing += ok;
    for (const auto& t : e.targets) {
      std::snprintf(line, sizeof line, "%-28s %7.2f %9d %10.3f %11.3f %9.2f  %s\n", e.id.c_str(), t.target,
                    t.episodes, t.mean_speed, t.speed_error, t.fall_rate, ok ? "yes" : "no");
      out += line;
    }
  }
  std::snprintf(line, sizeof line, "\n%d of %zu experts pass (every target within 0.3 m/s, falls < 10%%)\n",
                passing, evaluations.size());
  return out + line;
}

}  // namespace vaegail
