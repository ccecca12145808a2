// Demonstration files (data/demos.h) as VAE training data, with the train / validation split
// of the paper's generalisation experiments: validation = the held-out experts' episodes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "data/demos.h"
#include "vae/vae_config.h"
#include "vae/vae_trainer.h"

namespace vaegail::vae {

// Episodes of unequal lengths are padded with zeros to the longest; the mask [M, T] is then
// defined (true on real steps). Equal lengths: mask undefined (the trainer's fast path).
// Throws std::invalid_argument when obs/act sizes differ from the config's state/action dims.
TrajectoryDataset to_trajectory_dataset(const DemoSet& demos, const std::vector<int64_t>& episodes,
                                        const VaeConfig& config);

struct DemoSplit {
  std::vector<int64_t> train, val;  // episode indices into DemoSet::episodes, ascending
};

// Training: episodes with attribute held_out == 0 (or no such attribute); validation: the
// held-out ones. Without any held-out episode, a seeded `val_fraction` of all episodes (at
// least one when there are two or more) is moved to validation instead.
DemoSplit split_demos(const DemoSet& demos, std::uint64_t seed, double val_fraction = 0.1);

struct DemoTrainingData {
  DemoSet demos;
  DemoSplit split;
  TrajectoryDataset train, val;
};

// Dimension check + split + tensors. Errors name the file.
DemoTrainingData make_demo_training_data(DemoSet demos, const VaeConfig& config,
                                         std::uint64_t split_seed);

// Per-episode scalars the VAE commands report.
bool is_held_out(const Episode& episode);
// The episode's mean forward speed: attribute mean_com_speed when recorded, otherwise the
// mean of the com_speed feature; throws DataError when the file has neither.
double achieved_speed(const DemoSet& demos, int64_t episode);
// The same, NaN for a file without a speed (the arm's).
double achieved_speed_or_nan(const DemoSet& demos, int64_t episode);

}  // namespace vaegail::vae
