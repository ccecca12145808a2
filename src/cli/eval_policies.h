// The policies the evaluations compare: the VAE policy's mean action (when `model` is not
// empty) and, when their run directories are given, the diverse-GAIL (which needs the VAE),
// plain-GAIL and behaviour-cloning policies.
#pragma once

#include <torch/torch.h>

#include <string>
#include <vector>

#include "env/env.h"
#include "eval/walker_eval.h"
#include "vae/trajectory_vae.h"

namespace vaegail::cli {

struct PolicyRuns {
  std::string gail, plain, bc;  // run directories; empty: not compared
};

std::vector<eval::NamedPolicy> load_policies(const vae::TrajectoryVae& model, const Env& env, const PolicyRuns& runs,
                                             torch::Device device);

}  // namespace vaegail::cli
