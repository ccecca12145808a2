// The interface the on-policy updates (TRPO, PPO) and the rollout see: a module that maps a
// policy input to a diagonal Gaussian over actions. GaussianPolicy is the plain MLP version;
// the GAIL stage plugs in a residual policy N(μθ(x,z) + μα(x,z), σθ) behind the same interface.
//
// Shapes: input [B, input_dim] (normalised observation ++ condition), actions [B, act_dim].
#pragma once

#include <torch/torch.h>

#include <vector>

namespace vaegail {

// A batch of diagonal Gaussians; mean and log_std are both [B, act_dim].
struct DiagGaussian {
  torch::Tensor mean;
  torch::Tensor log_std;

  // [B, act_dim] → [B]: log density, summed over action dimensions.
  torch::Tensor log_prob(const torch::Tensor& actions) const;
  // [B]
  torch::Tensor entropy() const;
  // [B, act_dim]. The noise is drawn on the CPU from `generator` and moved to the mean's
  // device, so a seed gives the same actions on every device.
  torch::Tensor sample(torch::Generator& generator) const;
  DiagGaussian detached() const { return {mean.detach(), log_std.detach()}; }
};

// KL(p ‖ q) per sample, [B], in closed form.
torch::Tensor kl_divergence(const DiagGaussian& p, const DiagGaussian& q);

class StochasticPolicy : public torch::nn::Module {
 public:
  virtual int input_dim() const = 0;
  virtual int act_dim() const = 0;
  // [B, input_dim] → distribution with [B, act_dim] parameters.
  virtual DiagGaussian distribution(const torch::Tensor& input) = 0;
  // The part of the mean that no update moves, [B, act_dim], or an undefined tensor where there
  // is none. The residual policy's frozen VAE mean is most of its forward cost: an update computes
  // it once per batch and passes it to distribution_with() at every evaluation of the batch.
  virtual torch::Tensor frozen_mean(const torch::Tensor& /*input*/) { return {}; }
  // distribution(input), given frozen = frozen_mean(input) computed beforehand.
  virtual DiagGaussian distribution_with(const torch::Tensor& input, const torch::Tensor& /*frozen*/) {
    return distribution(input);
  }
  // The parameters a policy update moves: those that require gradients (a residual policy's
  // frozen base does not).
  std::vector<torch::Tensor> trainable_parameters() const;
};

}  // namespace vaegail
