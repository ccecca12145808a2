// The demonstrations as the adversarial stage uses them: every step (x_t, a_t) of the
// training episodes in one table, each episode's posterior q(z | τ) and its context.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <vector>

#include "data/demos.h"
#include "rl/distributed.h"
#include "util/rng.h"
#include "vae/trajectory_vae.h"

namespace vaegail {

struct GailDemos {
  std::vector<int64_t> episodes;               // [M] indices into the DemoSet
  std::vector<std::vector<double>> contexts;   // [M] each episode's environment context
  torch::Tensor observations;                  // [S, obs_dim] x_1..x_T of every episode, concatenated (CPU)
  torch::Tensor actions;                       // [S, act_dim] a_1..a_T, aligned with observations
  torch::Tensor offsets, lengths;              // [M] int64: episode m holds rows offsets[m] .. + lengths[m]
  torch::Tensor mu, sigma;                     // [M, Z] q(z | τ_m); Z = 0 without a VAE
  std::vector<double> achieved_speeds;         // [M] mean forward speed; NaN where the file records none

  int size() const { return static_cast<int>(episodes.size()); }
  int latent_dim() const { return static_cast<int>(mu.size(1)); }
  // One reparameterised draw z = μ_m + σ_m·ε of episode m's posterior (empty when Z = 0).
  std::vector<float> sample_latent(int m, Rng& rng) const;
  // For each entry of `episode` [B] (int64), the (x, a) of a uniformly drawn step of that
  // episode: observations [B, obs_dim], actions [B, act_dim]. `slice`: where the B entries are
  // one rank's share of a run's (rl/distributed.h), their global rows: the draws are then made
  // for every row of the run, whatever the ranks (default: these are all).
  std::pair<torch::Tensor, torch::Tensor> sample_steps(const torch::Tensor& episode, torch::Generator& generator,
                                                       const RowSlice& slice = {}) const;
};

// `vae` may be null (plain GAIL, behaviour cloning): no latent then. With a VAE, the
// episodes' dimensions must match its config (std::invalid_argument naming the file).
GailDemos make_gail_demos(const DemoSet& demos, const std::vector<int64_t>& episodes, vae::TrajectoryVae* vae);

}  // namespace vaegail
