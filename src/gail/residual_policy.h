// The policy of the adversarial stage (paper section 3.2):
//
//   π_θ(· | x, z) = N(μ_θ(x, z) + μ_α(x, z), σ_θ)
//
// μ_α is the trained VAE's action-decoder mean, frozen (no gradient, not among the
// trainable parameters, so TRPO only moves θ); μ_θ is an MLP whose last layer starts near 0,
// so the policy starts as the VAE policy plus exploration noise instead of an untrained
// network (the paper's reason: noise on a from-scratch policy makes early rollouts useless).
// σ_θ is a learned vector, initially exp(-1) (Table 3, walker).
//
// It is a StochasticPolicy on the Agent's input, normalise(x) ++ z, [B, obs_dim + latent_dim].
// μ_α needs the raw state, which is recovered by inverting the agent's normaliser: that
// normaliser must be frozen (the GAIL stage fixes it to the demonstrations' statistics), or a
// rollout's stored inputs would decode to other states at update time. States beyond the
// normaliser's clip (±10 std) reach μ_α clipped there.
#pragma once

#include <memory>
#include <vector>

#include "rl/mlp.h"
#include "rl/obs_normalizer.h"
#include "rl/stochastic_policy.h"
#include "vae/trajectory_vae.h"

namespace vaegail {

struct ResidualPolicyOptions {
  std::vector<int> hidden = {200, 100};  // Table 2, walker
  Activation activation = Activation::Tanh;
  double init_log_std = -1.0;  // Table 3, walker: initial std exp(-1)
  double output_gain = 0.01;   // μ_θ's last layer: near 0
};

class ResidualPolicy : public StochasticPolicy {
 public:
  // `base` is registered as a submodule (a checkpoint holds it, `to(device)` moves it) with
  // its parameters frozen. `normalizer` is the agent's; it is shared, not owned.
  ResidualPolicy(vae::TrajectoryVae base, std::shared_ptr<const ObsNormalizer> normalizer,
                 const ResidualPolicyOptions& options = {});

  int input_dim() const override { return residual_->in_dim(); }
  int act_dim() const override { return residual_->out_dim(); }
  DiagGaussian distribution(const torch::Tensor& input) override;
  // μ_α(x, z) for input [B, input_dim], without gradient: [B, act_dim].
  torch::Tensor frozen_mean(const torch::Tensor& input) override;
  DiagGaussian distribution_with(const torch::Tensor& input, const torch::Tensor& frozen) override;

 private:
  vae::TrajectoryVae base_;
  std::shared_ptr<const ObsNormalizer> normalizer_;
  std::shared_ptr<Mlp> residual_;
  torch::Tensor log_std_;  // [act_dim]
};

}  // namespace vaegail
