#include "vae/action_decoder.h"

#include "vae/gaussian.h"

namespace vaegail::vae {

ActionDecoderImpl::ActionDecoderImpl(int64_t state_dim, int64_t latent_dim, int64_t action_dim,
                                     const std::vector<int>& hidden, bool state_dependent_std) {
  int64_t in = state_dim + latent_dim;
  for (int h : hidden) {
    hidden_->push_back(torch::nn::Linear(in, h));
    in = h;
  }
  register_module("hidden", hidden_);
  mean_ = register_module("mean", torch::nn::Linear(in, action_dim));
  if (state_dependent_std)
    log_std_ = register_module("log_std", torch::nn::Linear(in, action_dim));
  else
    shared_log_std_ = register_parameter("shared_log_std", torch::zeros({action_dim}));
}

torch::Tensor ActionDecoderImpl::trunk(const torch::Tensor& state, const torch::Tensor& z) {
  auto h = torch::cat({state, z}, -1);
  for (const auto& layer : *hidden_) h = torch::tanh(layer->as<torch::nn::Linear>()->forward(h));
  return h;
}

ActionDistribution ActionDecoderImpl::forward(const torch::Tensor& state, const torch::Tensor& z) {
  const auto h = trunk(state, z);
  auto mean = mean_(h);
  auto log_std = log_std_ ? log_std_(h) : shared_log_std_.expand_as(mean);
  return {mean, soft_bound(log_std, kMinLogStd, kMaxLogStd)};
}

torch::Tensor ActionDecoderImpl::mean(const torch::Tensor& state, const torch::Tensor& z) {
  return mean_(trunk(state, z));
}

torch::Tensor ActionDecoderImpl::log_prob(const torch::Tensor& state, const torch::Tensor& z,
                                          const torch::Tensor& action) {
  const auto d = forward(state, z);
  return gaussian_log_prob(action, d.mean, d.log_std).sum(-1);
}

}  // namespace vaegail::vae
