// Generalised advantage estimation, GAE(λ) (Schulman et al. 2016), over time-major [T, N]
// tensors as a Rollout holds them.
#pragma once

#include <torch/torch.h>

namespace vaegail {

struct Advantages {
  torch::Tensor advantages;  // [T, N]
  torch::Tensor returns;     // [T, N]: advantages + values, the critic's regression target
};

// δ_t = r_t + γ·next_value_t·(1 − terminated_t) − value_t
// A_t = δ_t + γλ·(1 − done_t)·A_{t+1}, done = terminated or truncated, A_T = 0.
// A truncated step still bootstraps from next_value (V of its final observation) but, like a
// terminated one, cuts the trace: the following step belongs to another episode.
Advantages compute_gae(const torch::Tensor& rewards, const torch::Tensor& values, const torch::Tensor& next_values,
                       const torch::Tensor& terminated, const torch::Tensor& truncated, double gamma, double lambda);

}  // namespace vaegail
