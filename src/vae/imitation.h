// One-shot imitation (paper section 4.2): roll a z-conditioned policy out from the initial
// states of demonstrations and measure what it achieves. Shared by the VAE's commands and the
// GAIL stage, so the policy is any function of (observations, z), not the VAE.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "vae/trained_vae.h"

namespace vaegail {
class Progress;
}

namespace vaegail::vae {

// Where an imitation starts: the demonstration's reset seed and context; with both the env
// reproduces the demonstration's initial state exactly.
struct RolloutStart {
  std::uint64_t seed = 0;
  std::vector<double> context;
};

std::vector<RolloutStart> rollout_starts(const DemoSet& demos, const std::vector<int64_t>& episodes);

struct ImitationOptions {
  int num_envs = 32;    // environments stepped together (the policy's batch)
  int num_threads = 1;  // threads stepping them
  std::string speed_feature = "com_speed";  // empty for tasks without one (the arm)
  std::string fallen_feature = "fallen";  // optional; terminations count as falls too
  // 0: each rollout from its start's own reset seed (the demonstration's initial state, as published); else from
  // derive_seed(start's seed, start_seed) (util/rng.h): a fresh initial state of the same distribution (the env's
  // reset noise), one per start and evaluation seed, so that an evaluation can be repeated over seeds.
  std::uint64_t start_seed = 0;
};

struct ImitationOutcome {
  double achieved_speed = 0;  // mean of speed_feature over the states the actions reached (0 without)
  bool fell = false;
  int fall_step = -1;  // the first step (0..T) whose state had fallen, or T on a termination; -1: none
  Episode episode;            // the whole rollout
};

// starts.size() episodes, each with its own row of z [M, Z]; results in start order.
std::vector<ImitationOutcome> roll_out_latent_policy(const Env& prototype,
                                                     const std::vector<RolloutStart>& starts,
                                                     const torch::Tensor& z,
                                                     const LatentPolicy& policy,
                                                     const ImitationOptions& options = {},
                                                     Progress* progress = nullptr);

// z for a batch of the running episodes at the control step each has reached: rows [n] (long,
// indices into the starts) and steps [n] (long, actions taken so far) -> z [n, Z] float CPU.
using LatentSchedule = std::function<torch::Tensor(const torch::Tensor& rows, const torch::Tensor& steps)>;

// As above, with the conditioning chosen per step (a transition between behaviours,
// eval/transitions.h); the fixed-z rollout is the schedule that ignores the step.
std::vector<ImitationOutcome> roll_out_latent_policy(const Env& prototype,
                                                     const std::vector<RolloutStart>& starts,
                                                     const LatentSchedule& z,
                                                     const LatentPolicy& policy,
                                                     const ImitationOptions& options = {},
                                                     Progress* progress = nullptr);

// mu of q(z | x) for the given episodes, encoded in batches: [M, Z] on the CPU (and sigma when
// asked for). `progress` advances by one per episode.
torch::Tensor encode_episodes(TrajectoryVae& model, const DemoSet& demos, const std::vector<int64_t>& episodes,
                              torch::Tensor* sigma = nullptr, Progress* progress = nullptr);

// The median; 0 for none.
double median(std::vector<double> values);
// Median of |a - b| over pairs; 0 for none.
double median_abs_difference(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace vaegail::vae
