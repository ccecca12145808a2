#include "rl/critic.h"

namespace vaegail {

Critic::Critic(const CriticOptions& options)
    : net_(register_module("net", std::make_shared<Mlp>(options.input_dim, options.hidden, 1, options.activation))) {}

torch::Tensor Critic::forward(const torch::Tensor& input) { return net_->forward(input).squeeze(-1); }

}  // namespace vaegail
