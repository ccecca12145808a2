#include "rl/stochastic_policy.h"

#include <cmath>

namespace vaegail {

namespace {
const double kLog2Pi = std::log(2.0 * M_PI);
}

torch::Tensor DiagGaussian::log_prob(const torch::Tensor& actions) const {
  const auto z = (actions - mean) * torch::exp(-log_std);
  return (-0.5 * z.pow(2) - log_std - 0.5 * kLog2Pi).sum(-1);
}

torch::Tensor DiagGaussian::entropy() const { return (log_std + 0.5 * (kLog2Pi + 1.0)).sum(-1); }

torch::Tensor DiagGaussian::sample(torch::Generator& generator) const {
  const auto noise =
      torch::randn(mean.sizes(), generator, torch::TensorOptions().dtype(mean.dtype())).to(mean.device());
  return mean + torch::exp(log_std) * noise;
}

torch::Tensor kl_divergence(const DiagGaussian& p, const DiagGaussian& q) {
  const auto var_ratio = torch::exp(2.0 * (p.log_std - q.log_std));
  const auto mean_term = (p.mean - q.mean).pow(2) * torch::exp(-2.0 * q.log_std);
  return (q.log_std - p.log_std + 0.5 * (var_ratio + mean_term - 1.0)).sum(-1);
}

std::vector<torch::Tensor> StochasticPolicy::trainable_parameters() const {
  std::vector<torch::Tensor> out;
  for (const auto& p : parameters())
    if (p.requires_grad()) out.push_back(p);
  return out;
}

}  // namespace vaegail
