#include "experts/expert_eval.h"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <string>

#include "experts/agent_policy.h"
#include "util/rng.h"

namespace vaegail {

bool ExpertEvaluation::passes(double max_error, double max_fall_rate) const {
  for (const auto& t : targets)
    if (!(t.speed_error <= max_error) || t.fall_rate >= max_fall_rate) return false;
  return !targets.empty();
}

ExpertEvaluation evaluate_expert(const LoadedExpert& expert, const ExpertEvalOptions& o) {
  // The humanoid's context is a style label, with no speed to grade the expert against.
  if (expert.spec.task == "humanoid")
    throw std::invalid_argument("experts eval: " + expert.spec.id +
                                " runs the humanoid, whose demonstrators are gait controllers: "
                                "experts eval --task humanoid --styles FILE...");
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
    t.label = fmt::format("{:.2f}", target);
    t.target_speed = target;
    t.episodes = static_cast<int>(episodes.size());
    for (const auto& e : episodes) {
      t.mean_speed += e.attributes.at("mean_com_speed") / t.episodes;
      t.fall_rate += (e.terminations.back() ? 1.0 : 0.0) / t.episodes;
    }
    t.speed_error = std::abs(t.mean_speed - t.target_speed);
    result.targets.push_back(t);
  }
  return result;
}

std::string format_evaluations(const std::vector<ExpertEvaluation>& evaluations) {
  std::string out = fmt::format("{:<28} {:>7} {:>9} {:>10} {:>11} {:>9}  {}\n", "expert", "target", "episodes",
                                "mean speed", "|mean-tgt|", "fall rate", "passes");
  int passing = 0;
  for (const auto& e : evaluations) {
    const bool ok = e.passes();
    passing += ok;
    for (const auto& t : e.targets)
      out += fmt::format("{:<28} {:>7} {:9} {:10.3f} {:11.3f} {:9.2f}  {}\n", e.id, t.label, t.episodes, t.mean_speed,
                         t.speed_error, t.fall_rate, ok ? "yes" : "no");
  }
  return out + fmt::format("\n{} of {} experts pass (every target within 0.3 m/s, falls < 10%)\n", passing,
                           evaluations.size());
}

}  // namespace vaegail
