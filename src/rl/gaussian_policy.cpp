#include "rl/gaussian_policy.h"

namespace vaegail {

GaussianPolicy::GaussianPolicy(const GaussianPolicyOptions& options)
    : mean_(register_module("mean", std::make_shared<Mlp>(options.input_dim, options.hidden, options.act_dim,
                                                          options.activation, options.output_gain))),
      log_std_(register_parameter("log_std", torch::full({options.act_dim}, options.init_log_std))) {}

DiagGaussian GaussianPolicy::distribution(const torch::Tensor& input) {
  auto mean = mean_->forward(input);
  return {mean, log_std_.expand_as(mean)};
}

}  // namespace vaegail
