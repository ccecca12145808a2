// Does the action decoder read z? The teacher-forced error of pi's mean action against a
// demonstration's actions, given the demonstration's own states and a chosen z: with the
// episode's own embedding, with another episode's, and with z = 0. A decoder that ignores z
// (the copycat failure: the state alone tells the next action) shows the same error for all
// three; one that reads z shows the own-z error far below the others.
#pragma once

#include <torch/torch.h>

#include <string>
#include <vector>

#include "vae/trajectory_vae.h"
#include "vae/vae_trainer.h"

namespace vaegail::vae {

// Root mean squared action error (raw units), over the first step and over the later ones.
struct ActionError {
  double first_step = 0;
  double later_steps = 0;
};

// data: the demonstrations (states [M, T+1, D], actions [M, T, A], optional mask); z [M, Z].
ActionError teacher_forced_action_error(TrajectoryVae& model, const TrajectoryDataset& data,
                                        const torch::Tensor& z);

struct ActionErrorRow {
  std::string z_source;  // "own", "another episode's", "zero"
  ActionError error;
};

// The three rows for data encoded as mu [M, Z]; "another episode's" is mu rolled by M / 2
// (with episodes grouped by expert, mostly another expert's).
std::vector<ActionErrorRow> action_error_by_z_source(TrajectoryVae& model,
                                                     const TrajectoryDataset& data,
                                                     const torch::Tensor& mu);

}  // namespace vaegail::vae
