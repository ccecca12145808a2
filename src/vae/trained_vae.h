// A trained VAE for inference: loading a `vae train` checkpoint, the posterior of trajectories,
// and the action decoder's mean as a z-conditioned policy. Apart from the trainer so that the
// deployment library (src/controller) links the model without the training code.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "vae/trajectory_vae.h"

namespace vaegail::vae {

// observations [N, obs_dim] float CPU, z [N, Z] float CPU -> actions [N, act_dim] (any float
// tensor, any device). Called once per control step with the episodes still running.
using LatentPolicy = std::function<torch::Tensor(const torch::Tensor& observations,
                                                 const torch::Tensor& z)>;

// Loads the model alone (config read from the file) from a `vae train` run: its directory, a
// trainer checkpoint (RUN/checkpoints/latest.pt) or a weights file (util/checkpoint_file.h's
// model_file). A missing or damaged file, or the weights file of another kind of model, throws
// one line naming it.
TrajectoryVae load_trained_vae(const std::string& run, const torch::Device& device = torch::kCPU);

// Writes the weights file of `model` (kind "vae": its config and parameters, no optimiser state)
// to `path`, atomically; a failed write throws one line naming it. `epochs`, when >= 0, records
// how many epochs trained it (the trainer's own copy, which a run resumes from: vae_trainer.h).
void save_vae_weights(const TrajectoryVae& model, const std::string& path, int epochs = -1);

// (mu, sigma) [M, Z] of q(z | states) for every trajectory, in batches, without gradient,
// returned on the CPU. states [M, T+1, D] raw; step_mask [M, T] optional (as in the dataset).
std::pair<torch::Tensor, torch::Tensor> encode(TrajectoryVae& model, const torch::Tensor& states,
                                               const torch::Tensor& step_mask = {},
                                               int64_t batch_size = 64);

// The VAE policy's mean action π_α(x, z), the imitation the paper evaluates.
LatentPolicy vae_mean_policy(TrajectoryVae model, torch::Device device);

}  // namespace vaegail::vae
