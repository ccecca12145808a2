#include "experts/demo_collection.h"

#include <stdexcept>

#include "data/record.h"
#include "experts/agent_policy.h"
#include "experts/expert_trainer.h"
#include "util/rng.h"

namespace vaegail {

void collect_demos(const std::vector<std::string>& expert_dirs, const std::string& out_path,
                   const CollectOptions& o, Progress* progress) {
  std::vector<LoadedExpert> experts;
  for (const auto& dir : expert_dirs) {
    experts.push_back(load_expert(dir));
    if (experts.back().spec.task != experts.front().spec.task)
      throw std::invalid_argument(dir + ": a " + experts.back().spec.task + " expert among " +
                                  experts.front().spec.task + " experts (one file holds one task)");
  }
  if (experts.empty()) throw std::invalid_argument("collect_demos: no experts");
  const auto prototype = make_expert_env(experts.front().spec);
  DemoWriter writer(out_path, header_for(*prototype));
  for (size_t x = 0; x < experts.size(); ++x) {
    const LoadedExpert& expert = experts[x];
    const auto& targets = expert.spec.targets;
    RecordRequest request;
    std::vector<std::vector<float>> conditions;
    for (int k = 0; k < o.episodes_per_expert; ++k) {
      const double target = targets[k % targets.size()];
      request.seeds.push_back(derive_seed(derive_seed(o.seed, x), k));
      request.contexts.push_back({target});
      conditions.push_back(expert.spec.condition_for(target));
    }
    request.expert_id = expert.spec.id;
    request.num_envs = o.num_envs;
    request.num_threads = o.threads;
    auto episodes = record_episodes(*prototype, request,
                                    agent_batch_policy(expert.agent, conditions, o.stochastic,
                                                       derive_seed(o.seed, 1000 + x)),
                                    progress);
    for (auto& e : episodes) {
      e.attributes["held_out"] = o.held_out.count(expert.spec.id) ? 1.0 : 0.0;
      e.attributes["init_log_std"] = expert.spec.init_log_std;
      writer.append(e);
    }
  }
  writer.commit();
}

}  // namespace vaegail
