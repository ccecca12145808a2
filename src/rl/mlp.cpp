#include "rl/mlp.h"

#include <cmath>
#include <string>

namespace vaegail {

namespace {

torch::nn::Linear make_layer(int in, int out, double gain) {
  torch::nn::Linear layer(in, out);
  torch::NoGradGuard no_grad;
  torch::nn::init::orthogonal_(layer->weight, gain);
  torch::nn::init::zeros_(layer->bias);
  return layer;
}

}  // namespace

Mlp::Mlp(int in_dim, const std::vector<int>& hidden, int out_dim, Activation activation, double output_gain)
    : in_dim_(in_dim), out_dim_(out_dim), activation_(activation) {
  const double hidden_gain = activation == Activation::Relu ? std::sqrt(2.0) : 5.0 / 3.0;
  int width = in_dim;
  for (size_t i = 0; i <= hidden.size(); ++i) {
    const bool last = i == hidden.size();
    const int next = last ? out_dim : hidden[i];
    layers_.push_back(register_module("layer" + std::to_string(i),
                                      make_layer(width, next, last ? output_gain : hidden_gain)));
    width = next;
  }
}

torch::Tensor Mlp::forward(torch::Tensor x) {
  for (size_t i = 0; i < layers_.size(); ++i) {
    x = layers_[i]->forward(x);
    if (i + 1 < layers_.size()) x = activation_ == Activation::Relu ? torch::relu(x) : torch::tanh(x);
  }
  return x;
}

}  // namespace vaegail
