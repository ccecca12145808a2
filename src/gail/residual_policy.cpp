#include "gail/residual_policy.h"

#include <stdexcept>
#include <string>

namespace vaegail {

namespace {
// ObsNormalizer's variance epsilon (rl/obs_normalizer.cpp): the inverse must use the same.
constexpr double kNormalizerVarEpsilon = 1e-8;
}  // namespace

ResidualPolicy::ResidualPolicy(vae::TrajectoryVae base, std::shared_ptr<const ObsNormalizer> normalizer,
                               const ResidualPolicyOptions& options)
    : base_(register_module("base", std::move(base))), normalizer_(std::move(normalizer)) {
  const auto& c = base_->config();
  if (normalizer_->dim() != c.state_dim)
    throw std::invalid_argument("ResidualPolicy: the observation has " + std::to_string(normalizer_->dim()) +
                                " components, the VAE's state " + std::to_string(c.state_dim));
  for (auto& p : base_->parameters()) p.set_requires_grad(false);
  residual_ = register_module("residual", std::make_shared<Mlp>(c.state_dim + c.latent_dim, options.hidden,
                                                                c.action_dim, options.activation,
                                                                options.output_gain));
  log_std_ = register_parameter("log_std", torch::full({c.action_dim}, options.init_log_std));
}

torch::Tensor ResidualPolicy::frozen_mean(const torch::Tensor& input) {
  torch::NoGradGuard no_grad;
  const int obs_dim = normalizer_->dim();
  const auto scale = torch::sqrt(normalizer_->var() + kNormalizerVarEpsilon);
  const auto state = (input.slice(-1, 0, obs_dim).to(torch::kFloat64) * scale + normalizer_->mean());
  return base_->action_mean(state.to(input.scalar_type()), input.slice(-1, obs_dim));
}

DiagGaussian ResidualPolicy::distribution(const torch::Tensor& input) {
  return distribution_with(input, frozen_mean(input));
}

DiagGaussian ResidualPolicy::distribution_with(const torch::Tensor& input, const torch::Tensor& frozen) {
  auto mean = residual_->forward(input) + frozen;
  return {mean, log_std_.expand_as(mean)};
}

}  // namespace vaegail
