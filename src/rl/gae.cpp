#include "rl/gae.h"

namespace vaegail {

Advantages compute_gae(const torch::Tensor& rewards, const torch::Tensor& values, const torch::Tensor& next_values,
                       const torch::Tensor& terminated, const torch::Tensor& truncated, double gamma, double lambda) {
  torch::NoGradGuard no_grad;
  const auto deltas = rewards + gamma * next_values * (1 - terminated) - values;
  const auto continues = 1 - torch::clamp(terminated + truncated, 0, 1);
  auto advantages = torch::empty_like(deltas);
  auto running = torch::zeros_like(deltas[0]);
  for (int64_t t = deltas.size(0) - 1; t >= 0; --t) {
    running = deltas[t] + gamma * lambda * continues[t] * running;
    advantages[t] = running;
  }
  return {advantages, advantages + values};
}

}  // namespace vaegail
