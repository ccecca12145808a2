// A fully connected network: Linear → activation → … → Linear (no activation on the output).
#pragma once

#include <torch/torch.h>

#include <vector>

namespace vaegail {

enum class Activation { Tanh, Relu };

class Mlp : public torch::nn::Module {
 public:
  // Hidden layers get orthogonal weights with the activation's gain, so signals neither
  // vanish nor explode through depth. The output layer gets orthogonal weights scaled by
  // output_gain: a small gain (0.01) makes a policy start near its mean-zero prior.
  Mlp(int in_dim, const std::vector<int>& hidden, int out_dim, Activation activation = Activation::Tanh,
      double output_gain = 1.0);

  // [B, in_dim] → [B, out_dim]
  torch::Tensor forward(torch::Tensor x);

  int in_dim() const { return in_dim_; }
  int out_dim() const { return out_dim_; }

 private:
  int in_dim_, out_dim_;
  Activation activation_;
  std::vector<torch::nn::Linear> layers_;
};

}  // namespace vaegail
