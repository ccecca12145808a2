// The VAE policy trained on past its joint training: the action decoder pi(a | x, z) fitted to
// the demonstrations' steps with the encoder and the state decoder frozen and each step's z the
// encoder's mean for its trajectory.
//
// Why: the joint VAE takes one Adam step per batch of whole trajectories, and the encoder and
// the WaveNet state decoder set its pace (minutes per epoch on the humanoid). Sixty epochs of 250
// humanoid demonstrations are under a thousand steps for the action decoder, while a plain MLP
// cloning the same controller takes thousands of steps over shuffled single steps
// (../shared/reference/held_torque_dagger: batch 256, 30 epochs).
//
// The loss is the squared error of the mean action in raw units (torque fractions), not the
// VAE's -log pi: with a learned std per component, the likelihood weighs each component's error
// by 1 / std^2, and the humanoid's near-constant hand motors (action std 3e-4 in the clean
// demonstrations) then claim the shared hidden layers while the legs (std 0.3-0.75) stay at a
// fifth of their std in error. Raw units weigh every motor by its torque, as the reference's
// behaviour cloning does; the log-std head is left as it was (the policy acts on the mean, and
// GAIL's residual brings its own std). The model that comes out is the same VAE with other
// action-decoder weights, so every command that loads a VAE (imitate, eval, gail train --vae)
// takes it as it is.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <string>
#include <vector>

#include "vae/trajectory_vae.h"
#include "vae/vae_trainer.h"

namespace vaegail::vae {

// The real steps of a set of trajectories as rows, normalised as the model sees them.
struct StepRecords {
  torch::Tensor x, z, a;  // [N, D], [N, Z], [N, A]
  int64_t size() const { return x.defined() ? x.size(0) : 0; }
};

// Each trajectory's steps with z = mu [M, Z] of that trajectory.
StepRecords step_records(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& mu);

// Each target row's z borrowed from a source row of the same label: for every target i, the mu
// of a source row j with source_labels[j] == target_labels[i], drawn uniformly (seeded). Why:
// noise-perturbed (DART) demonstrations lie off the paths the encoder was trained on, and it
// does not tell their styles apart (humanoid: 25% nearest-centroid, chance 17%), so their own
// mu says nothing and a policy fitted on them learns to ignore z; the mu of a clean
// demonstration of the same style carries the style as one-shot imitation will present it.
// Throws std::invalid_argument naming a target label no source row has.
torch::Tensor latents_by_label(const torch::Tensor& source_mu, const std::vector<double>& source_labels,
                               const std::vector<double>& target_labels, std::uint64_t seed);

// Mean over the rows of -log pi(a | x, z) (summed over the action components) and the root
// mean squared error of the mean action in raw action units (the normalised error times the
// action std): no gradient.
struct PolicyFit {
  double nll = 0, rmse = 0;
};
PolicyFit policy_fit(TrajectoryVae& model, const StepRecords& records, int64_t batch = 4096);

struct PolicyRefitOptions {
  std::string out_dir;  // weights.pt, metrics.csv, checkpoints/latest.pt
  int epochs = 30;
  int64_t batch = 256;
  double learning_rate = 1e-3;  // cosine-decayed to learning_rate / 100 over the epochs
  std::uint64_t seed = 0;
  bool progress = true;
};

// Trains model's action decoder in place on `train` (rows shuffled per epoch, seeded by
// (seed, epoch)), evaluating on `val` (may be empty) after each epoch. After each epoch a
// metrics row, out_dir/checkpoints/latest.pt (the whole model, readable by load_trained_vae,
// with Adam's state and the epoch) and out_dir/weights.pt are written atomically; a call whose
// out_dir holds latest.pt resumes from it; out_dir's run lock (util/run_lock.h) is held meanwhile.
// Returns the fit after the last epoch.
struct PolicyRefitResult {
  int epochs_run = 0;  // in this call
  PolicyFit before_train, before_val, train, val;  // val: NaN without validation rows
};
PolicyRefitResult refit_policy(TrajectoryVae& model, const StepRecords& train, const StepRecords& val,
                               const PolicyRefitOptions& options);

}  // namespace vaegail::vae
