// Training loop of the trajectory VAE: epochs of shuffled minibatches over an in-memory
// dataset, Adam, a validation pass per epoch, metrics as CSV, atomic checkpoints, resume.
//
// Run directory layout (created as needed):
//   run_dir/config.json                 the VaeConfig
//   run_dir/metrics.csv                 one row per epoch: every loss term, train and val
//   run_dir/checkpoints/latest.pt       model + optimizer + epoch + seed, written atomically
//   run_dir/checkpoints/epoch_{e}.pt    the same after every epoch e, with keep_epochs
//   run_dir/weights.pt                  the model alone and the epoch (trained_vae.h's weights file),
//                                       after every epoch: what a repository keeps of a run that spans
//                                       sessions (a third of latest.pt: no Adam moments). A run
//                                       directory holding it and no checkpoint resumes from it at its
//                                       epoch, Adam's moments starting afresh (the one difference
//                                       from an uninterrupted run).
//
// Reproducibility: every random stream is derived from (seed, epoch, batch) with
// util/rng.h's derive_seed: the weight initialisation, the epoch's shuffle and each batch's
// reparameterisation noise and encoder input noise (drawn on the CPU, then moved to the
// device). The RNG state of a checkpoint is therefore just (seed, epoch), and a run resumed from
// epoch e reproduces the uninterrupted run exactly (same thread count, CPU).
//
// Ranks (util/world.h, rl/distributed.h): under `mpirun -np K` every rank builds the same model
// and holds the whole data set, and each batch of B trajectories is shared by the ranks
// (EnvSlice::share: contiguous, uneven when K does not divide B). A rank's loss is the sum over
// its rows divided by B, the gradients are summed over the ranks, and every rank takes the same
// Adam step; noise is drawn for the whole batch and sliced. K ranks therefore train what one
// process trains, to float rounding (VaeTrainerRanksTest in vae_trainer_test.cpp), and the
// logged loss terms are the run's. Rank 0 alone writes config.json, metrics.csv and the
// checkpoints; every rank reads latest.pt when resuming, and a run may resume under another K.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "util/run_lock.h"
#include "vae/trained_vae.h"
#include "vae/trajectory_vae.h"
#include "vae/vae_config.h"

namespace vaegail::vae {

// M trajectories: states [M, T+1, D], actions [M, T, A], mask [M, T] (optional).
struct TrajectoryDataset {
  torch::Tensor states, actions, mask;
  int64_t size() const { return states.defined() ? states.size(0) : 0; }
  // The rows `index` [K] (int64), on `device`.
  TrajectoryDataset select(const torch::Tensor& index, const torch::Device& device) const;
  void validate(const VaeConfig& config) const;  // throws std::invalid_argument
};

struct TrainerOptions {
  std::string run_dir;        // required
  int epochs = 100;           // train() stops after this many epochs in total
  uint64_t seed = 0;
  torch::Device device = torch::kCPU;
  bool progress = true;       // a progress bar on stderr
  int eval_batch_size = 64;   // batch size of validation passes
  // Also keep every epoch's checkpoint: an epoch is chosen after the run, by a criterion the
  // validation loss does not measure (imitation in the environment, an embedding test).
  bool keep_epochs = false;
};

// Batch-mean loss terms of a pass over a dataset, weighted by batch size.
struct LossTerms {
  double total = 0, action_nll = 0, state_nll = 0, kl = 0;
};

struct EpochMetrics {
  int epoch = 0;  // 1-based
  LossTerms train, val;
  double seconds = 0;
  double train_seconds = 0;  // of which the minibatches (not validation or writing)
};

class VaeTrainer {
 public:
  // Builds the model (seeded), fits its normalisation on `train`, and resumes from
  // run_dir/checkpoints/latest.pt when that exists (its config must equal `config`). Holds
  // run_dir for its life (util/run_lock.h: a second trainer on it is refused).
  VaeTrainer(const VaeConfig& config, TrainerOptions options, TrajectoryDataset train,
             TrajectoryDataset val);

  // Runs epochs until options.epochs; returns the metrics of the epochs it ran.
  std::vector<EpochMetrics> train();
  EpochMetrics train_epoch();
  // Loss terms over a dataset (no gradient; noise from derive_seed(seed, epoch) so values
  // are comparable between calls in one epoch). Under mpirun every rank must call it (as
  // train_epoch does): each evaluates its share of every batch.
  LossTerms evaluate(const TrajectoryDataset& data);

  void save_checkpoint(const std::string& path);
  void load_checkpoint(const std::string& path);
  std::string weights_path() const;  // run_dir/weights.pt
  std::string checkpoint_path() const;
  std::string epoch_checkpoint_path(int epoch) const;
  std::string metrics_path() const;

  // The rate of minibatch `batch` (from 0) of epoch `epoch` (from 1): scheduled_learning_rate,
  // ramped up linearly over the first epoch after a resume from weights.pt alone. Why: Adam's
  // first steps from empty moments move every parameter by about the full rate (the
  // bias-corrected m / sqrt(v) is +-1 per coordinate), which jolts a trained model (the
  // humanoid VAE's loss went 4.8e4 -> 1.9e5 on the second batch after such a resume).
  double batch_learning_rate(int epoch, int64_t batch) const;

  int epoch() const { return epoch_; }  // epochs completed
  TrajectoryVae& model() { return model_; }
  torch::optim::Adam& optimizer() { return *optimizer_; }

 private:
  VaeConfig config_;
  TrainerOptions options_;
  RunLock lock_;
  TrajectoryDataset train_, val_;
  TrajectoryVae model_{nullptr};
  std::unique_ptr<torch::optim::Adam> optimizer_;
  int epoch_ = 0;
  int warmup_epoch_ = 0;  // the epoch whose rate ramps up (resume_from_weights); 0: none

  std::string checkpoint_file(const std::string& name) const;  // run_dir/checkpoints/name
  // The model and epoch of weights_path(); throws one line naming it for another config.
  void resume_from_weights();
};

// encode() of the dataset's states and mask (trained_vae.h).
std::pair<torch::Tensor, torch::Tensor> encode(TrajectoryVae& model,
                                               const TrajectoryDataset& data,
                                               int64_t batch_size = 64);

// The learning rate of epoch `epoch` (1-based): config.learning_rate, or with lr_decay_epochs
// E > 0 the cosine schedule lr * (1 + cos(pi * (epoch - 1) / E)) / 2, which starts at lr and
// reaches 0 after epoch E. Throws std::invalid_argument for an epoch past E (it would not learn).
double scheduled_learning_rate(const VaeConfig& config, int epoch);

}  // namespace vaegail::vae
