#include "vae/mixture.h"

#include "vae/gaussian.h"

namespace vaegail::vae {

torch::Tensor mixture_log_prob(const torch::Tensor& x, const MixtureParams& m) {
  const auto log_weights = torch::log_softmax(m.logits, -1);
  const auto per_component = gaussian_log_prob(x.unsqueeze(-1), m.means, m.log_stds);
  return torch::logsumexp(log_weights + per_component, -1);
}

torch::Tensor mixture_sample(const MixtureParams& m, c10::optional<at::Generator> generator) {
  torch::NoGradGuard no_grad;
  const auto cpu = torch::kCPU;
  const auto K = m.components();
  const auto weights = torch::softmax(m.logits.detach().to(cpu, torch::kFloat), -1);
  const auto flat = weights.reshape({-1, K});
  const auto pick = torch::multinomial(flat, 1, /*replacement=*/true, generator);  // [M, 1]
  const auto mean = m.means.detach().to(cpu, torch::kFloat).reshape({-1, K}).gather(1, pick);
  const auto log_std =
      m.log_stds.detach().to(cpu, torch::kFloat).reshape({-1, K}).gather(1, pick);
  const auto noise = at::randn(mean.sizes(), generator, torch::TensorOptions(torch::kFloat));
  auto sample = (mean + torch::exp(log_std) * noise).reshape(weights.sizes().slice(
      0, weights.dim() - 1));
  return sample.to(m.means.device(), m.means.scalar_type());
}

}  // namespace vaegail::vae
