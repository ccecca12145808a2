// State-value estimate V(input) on the same input as the policy.
#pragma once

#include <memory>
#include <vector>

#include "rl/mlp.h"

namespace vaegail {

struct CriticOptions {
  int input_dim = 0;
  std::vector<int> hidden = {200, 100};
  Activation activation = Activation::Tanh;
};

class Critic : public torch::nn::Module {
 public:
  explicit Critic(const CriticOptions& options);
  // [B, input_dim] → [B]
  torch::Tensor forward(const torch::Tensor& input);
  int input_dim() const { return net_->in_dim(); }

 private:
  std::shared_ptr<Mlp> net_;
};

}  // namespace vaegail
