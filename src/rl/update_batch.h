// A rollout flattened to B = T·N samples for a policy/critic update, and its minibatches.
#pragma once

#include <cstdint>
#include <vector>

#include "rl/rollout.h"

namespace vaegail {

struct UpdateBatch {
  torch::Tensor inputs;         // [B, input_dim]
  torch::Tensor actions;        // [B, act_dim]
  torch::Tensor old_log_probs;  // [B] under the policy that collected the data
  torch::Tensor advantages;     // [B] normalised to mean 0, std 1
  torch::Tensor returns;        // [B] critic targets (not normalised)

  int64_t size() const { return inputs.size(0); }
  UpdateBatch select(const torch::Tensor& indices) const;
  // A random partition into `count` minibatches of (almost) equal size.
  std::vector<UpdateBatch> minibatches(int count, torch::Generator& generator) const;
};

// GAE(γ, λ) on the rollout's rewards, then flattening. Both updates use normalised
// advantages: the step size then does not depend on the reward scale, which for GAIL
// changes as the discriminator trains.
UpdateBatch make_update_batch(const Rollout& rollout, double gamma = 0.99, double lambda = 0.95);

}  // namespace vaegail
