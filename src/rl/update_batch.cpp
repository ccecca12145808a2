#include "rl/update_batch.h"

#include <algorithm>

#include "rl/gae.h"

namespace vaegail {

UpdateBatch UpdateBatch::select(const torch::Tensor& indices) const {
  return {inputs.index_select(0, indices), actions.index_select(0, indices), old_log_probs.index_select(0, indices),
          advantages.index_select(0, indices), returns.index_select(0, indices)};
}

std::vector<UpdateBatch> UpdateBatch::minibatches(int count, torch::Generator& generator) const {
  const auto order = torch::randperm(size(), generator, torch::kLong).to(inputs.device());
  std::vector<UpdateBatch> out;
  for (const auto& part : order.tensor_split(std::max<int64_t>(1, std::min<int64_t>(count, size()))))
    out.push_back(select(part));
  return out;
}

UpdateBatch make_update_batch(const Rollout& rollout, double gamma, double lambda) {
  const auto gae = compute_gae(rollout.rewards, rollout.values, rollout.next_values, rollout.terminated,
                               rollout.truncated, gamma, lambda);
  const auto advantages = gae.advantages.reshape({-1});
  const auto flat = [](const torch::Tensor& x) { return x.reshape({-1, x.size(-1)}); };
  return {flat(rollout.inputs), flat(rollout.actions), rollout.log_probs.reshape({-1}),
          (advantages - advantages.mean()) / (advantages.std() + 1e-8), gae.returns.reshape({-1})};
}

}  // namespace vaegail
