// A rollout flattened to B = T·N samples for a policy/critic update, and its minibatches.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "rl/distributed.h"
#include "rl/rollout.h"

namespace vaegail {

struct UpdateBatch {
  torch::Tensor inputs;         // [B, input_dim]
  torch::Tensor actions;        // [B, act_dim]
  torch::Tensor old_log_probs;  // [B] under the policy that collected the data
  torch::Tensor advantages;     // [B] normalised to mean 0, std 1 over the run's batch
  torch::Tensor returns;        // [B] critic targets (not normalised)
  // Where these rows sit in the run's batch when it is spread over ranks (rl/distributed.h);
  // left empty, the batch is the whole of it.
  RowSlice rows;

  int64_t size() const { return inputs.size(0); }
  // The run's batch size: the denominator of every mean over the batch.
  int64_t global_size() const { return rows.global_rows.defined() ? rows.global_size : size(); }
  RowSlice row_slice() const { return rows.global_rows.defined() ? rows : RowSlice::whole(size()); }
  // The rows at local indices `indices`, part of a run's batch of `global_size` rows.
  UpdateBatch select(const torch::Tensor& indices, int64_t global_size) const;
  // A random partition of the run's batch into `count` minibatches of (almost) equal size, drawn
  // over its global rows (the same partition whatever the ranks); this rank's rows of each.
  std::vector<UpdateBatch> minibatches(int count, torch::Generator& generator) const;
  // The local rows whose global index is a multiple of `stride` (TRPO's Fisher subsample), as
  // local indices, and how many rows the run's subsample has.
  std::pair<torch::Tensor, int64_t> every(int stride) const;
};

// GAE(γ, λ) on the rollout's rewards, then flattening. Both updates use normalised
// advantages: the step size then does not depend on the reward scale, which for GAIL
// changes as the discriminator trains. `envs`: which of the run's environments the rollout's
// are (default: all of them).
UpdateBatch make_update_batch(const Rollout& rollout, double gamma = 0.99, double lambda = 0.95,
                              const EnvSlice& envs = {});

}  // namespace vaegail
