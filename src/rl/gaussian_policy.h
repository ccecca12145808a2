// The plain diagonal-Gaussian MLP policy: mean = MLP(input), log σ a learned vector shared by
// all states (the paper sweeps its initial value over {0, -1, -2, -3}).
#pragma once

#include <memory>
#include <vector>

#include "rl/mlp.h"
#include "rl/stochastic_policy.h"

namespace vaegail {

struct GaussianPolicyOptions {
  int input_dim = 0;  // observation dim + condition dim
  int act_dim = 0;
  std::vector<int> hidden = {200, 100};
  Activation activation = Activation::Tanh;
  double init_log_std = -1.0;
  double output_gain = 0.01;  // small initial means: early actions are mostly exploration noise
};

class GaussianPolicy : public StochasticPolicy {
 public:
  explicit GaussianPolicy(const GaussianPolicyOptions& options);

  int input_dim() const override { return mean_->in_dim(); }
  int act_dim() const override { return mean_->out_dim(); }
  DiagGaussian distribution(const torch::Tensor& input) override;

 private:
  std::shared_ptr<Mlp> mean_;
  torch::Tensor log_std_;  // [act_dim]
};

}  // namespace vaegail
