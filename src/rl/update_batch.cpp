#include "rl/update_batch.h"

#include <algorithm>
#include <cmath>

#include "rl/gae.h"

namespace vaegail {

UpdateBatch UpdateBatch::select(const torch::Tensor& indices, int64_t global_size) const {
  const auto rows_of = row_slice().global_rows.index_select(0, indices.to(torch::kCPU));
  const auto i = indices.to(inputs.device());
  return {inputs.index_select(0, i),     actions.index_select(0, i), old_log_probs.index_select(0, i),
          advantages.index_select(0, i), returns.index_select(0, i), RowSlice{rows_of, global_size}};
}

std::vector<UpdateBatch> UpdateBatch::minibatches(int count, torch::Generator& generator) const {
  const RowSlice slice = row_slice();
  const auto order = torch::randperm(slice.global_size, generator, torch::kLong);
  std::vector<UpdateBatch> out;
  for (const auto& part : order.tensor_split(std::max<int64_t>(1, std::min<int64_t>(count, slice.global_size))))
    out.push_back(select(slice.local_rows(part), part.size(0)));
  return out;
}

std::pair<torch::Tensor, int64_t> UpdateBatch::every(int stride) const {
  const RowSlice slice = row_slice();
  return {torch::nonzero(slice.global_rows.remainder(stride) == 0).reshape({-1}),
          (slice.global_size + stride - 1) / stride};
}

UpdateBatch make_update_batch(const Rollout& rollout, double gamma, double lambda, const EnvSlice& envs) {
  const auto gae = compute_gae(rollout.rewards, rollout.values, rollout.next_values, rollout.terminated,
                               rollout.truncated, gamma, lambda);
  const int64_t T = rollout.rewards.size(0), N = rollout.rewards.size(1);
  const RowSlice rows = RowSlice::of_rollout(T, envs.total > 0 ? envs : EnvSlice::whole(static_cast<int>(N)));
  // Normalised over the run's batch: the mean, then the unbiased variance about it.
  const auto advantages = gae.advantages.reshape({-1});
  const double n = static_cast<double>(rows.global_size);
  const double mean = all_sum(advantages.sum().item<double>()) / n;
  const double var = all_sum((advantages.to(torch::kFloat64) - mean).pow(2).sum().item<double>()) / std::max(n - 1, 1.0);
  const auto flat = [](const torch::Tensor& x) { return x.reshape({-1, x.size(-1)}); };
  return {flat(rollout.inputs),
          flat(rollout.actions),
          rollout.log_probs.reshape({-1}),
          (advantages - mean) / (std::sqrt(var) + 1e-8),
          gae.returns.reshape({-1}),
          rows};
}

}  // namespace vaegail
