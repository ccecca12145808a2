#include "experts/expert_eval.h"

#include <cmath>
#include <fmt/format.h>
#include <string>

#include "env/humanoid.h"
#include "experts/agent_policy.h"
#include "experts/humanoid_gait.h"
#include "util/rng.h"

namespace vaegail {

bool ExpertEvaluation::passes(double max_error, double max_fall_rate) const {
  for (const auto& t : targets)
    if (!(t.speed_error <= max_error) || t.fall_rate >= max_fall_rate) return false;
  return !targets.empty();
}

namespace {
// What a target asks of the episodes' speed, and under which recorded attribute the speed is.
struct SpeedGoal {
  std::string label;
  double speed;
  std::string attribute;
};

SpeedGoal speed_goal(const Env& env, double target) {
  if (const auto* humanoid = dynamic_cast<const HumanoidEnv*>(&env)) {
    const int style = static_cast<int>(target);
    return {humanoid->style_names().at(style), humanoid->style_target(style)[kForwardSpeed], "mean_forward_speed"};
  }
  return {fmt::format("{:.2f}", target), target, "mean_com_speed"};
}
}  // namespace

ExpertEvaluation evaluate_expert(const LoadedExpert& expert, const ExpertEvalOptions& o) {
  const auto prototype = make_expert_env(expert.spec);
  const bool humanoid = expert.spec.task == "humanoid";
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
    const SpeedGoal goal = speed_goal(*prototype, target);
    TargetResult t;
    t.target = target;
    t.label = goal.label;
    t.target_speed = goal.speed;
    t.episodes = static_cast<int>(episodes.size());
    if (humanoid) t.signature.assign(kGaitStatistics.size(), 0.0);
    for (const auto& e : episodes) {
      t.mean_speed += e.attributes.at(goal.attribute) / t.episodes;
      t.fall_rate += (e.terminations.back() ? 1.0 : 0.0) / t.episodes;
      if (!humanoid) continue;
      const GaitSignature g = gait_signature(e, prototype->feature_names(), prototype->control_timestep());
      for (size_t k = 0; k < g.size(); ++k) t.signature[k] += g[k] / t.episodes;
    }
    t.speed_error = std::abs(t.mean_speed - t.target_speed);
    result.targets.push_back(t);
  }
  return result;
}

std::string format_evaluations(const std::vector<ExpertEvaluation>& evaluations) {
  std::string out;
  const bool signatures = !evaluations.empty() && !evaluations.front().targets.empty() &&
                          !evaluations.front().targets.front().signature.empty();
  out += fmt::format("{:<28} {:>7} {:>9} {:>10} {:>11} {:>9}  {}", "expert", "target", "episodes", "mean speed",
                     "|mean-tgt|", "fall rate", "passes");
  if (signatures)
    for (size_t k = 1; k < kGaitStatistics.size(); ++k) out += std::string(" ") + kGaitStatistics[k];
  out += "\n";
  int passing = 0;
  for (const auto& e : evaluations) {
    const bool ok = e.passes();
    passing += ok;
    for (const auto& t : e.targets) {
      // The verdict is padded only where signature columns follow it.
      out += fmt::format("{:<28} {:>7} {:9} {:10.3f} {:11.3f} {:9.2f}  {:<{}}", e.id, t.label, t.episodes,
                         t.mean_speed, t.speed_error, t.fall_rate, ok ? "yes" : "no", signatures ? 6 : 0);
      // The signature's first statistic is the mean speed, already printed.
      for (size_t k = 1; k < t.signature.size(); ++k)
        out += fmt::format(" {:{}.3f}", t.signature[k], std::string(kGaitStatistics[k]).size());
      out += "\n";
    }
  }
  return out + fmt::format("\n{} of {} experts pass (every target within 0.3 m/s, falls < 10%)\n", passing,
                           evaluations.size());
}

}  // namespace vaegail
