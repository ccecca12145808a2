// One-shot imitation's z found by search rather than by one pass of the encoder: the mode of
// p(z | demonstration) under the trained decoders, reached by Adam from the encoder's mean,
//
//   minimise over z:  -log pi(a_{1:T} | x, z) - log p(x_{2:T+1} | x, z) + |z|^2 / 2.
//
// The encoder amortises this search over all demonstrations; for one unlike the training
// set's it can land away from the z the decoders explain it best with (the amortisation gap).
// Comparing imitations from the encoder's mean and from the refined z separates how much of an
// imitation's error is the encoder's and how much the decoders'. Each demonstration's z moves
// on its own: the objective is a sum over demonstrations and Adam acts per element.
#pragma once

#include <torch/torch.h>

#include <string>

#include "util/progress.h"
#include "vae/trajectory_vae.h"
#include "vae/vae_trainer.h"

namespace vaegail::vae {

struct RefineOptions {
  int steps = 100;
  double learning_rate = 0.05;
  int64_t batch = 64;  // demonstrations refined together
};

// The objective above for each demonstration: data [M], z [M, Z] -> [M].
torch::Tensor latent_objective(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& z);

// z [M, Z] (on the CPU) after options.steps Adam steps from `start` [M, Z]. `progress`
// advances by one per demonstration.
torch::Tensor refine_latents(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& start,
                             const RefineOptions& options = {}, Progress* progress = nullptr);

// refine_latents behind a progress bar, with the objective's mean over the demonstrations before
// and after, which say whether the search found anything the encoder missed.
struct RefinedLatents {
  torch::Tensor z;
  double objective_before = 0, objective_after = 0;
  std::string description;  // one line: the steps, the rate and the two means
};
RefinedLatents refine_with_report(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& start,
                                  const RefineOptions& options);

}  // namespace vaegail::vae
