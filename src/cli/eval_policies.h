// The policies the evaluations compare: the VAE policy's mean action (when `model` is not
// empty) and, when their run directories are given, the diverse-GAIL (which needs the VAE),
// plain-GAIL and behaviour-cloning policies.
#pragma once

#include <CLI/CLI.hpp>
#include <torch/torch.h>

#include <memory>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "eval/walker_eval.h"
#include "vae/trajectory_vae.h"

namespace vaegail::cli {

struct PolicyRuns {
  std::string gail, plain, bc;  // run directories; empty: not compared
};

std::vector<eval::NamedPolicy> load_policies(const vae::TrajectoryVae& model, const Env& env, const PolicyRuns& runs,
                                             torch::Device device);

// What an evaluation of imitations reads: --demos, --vae (both required), --gail, --plain, --bc.
struct EvalInputs {
  std::string demos, vae;
  PolicyRuns runs;
};
void add_eval_input_options(CLI::App& command, EvalInputs& inputs);
// --start-seed: the evaluation seed of the rollouts' starts (vae::ImitationOptions::start_seed).
void add_start_seed_option(CLI::App& command, vae::ImitationOptions& rollout);

// What an evaluation of imitations starts from: the demonstrations, the VAE that encodes them (in
// eval mode), the environment they were recorded in and the policies compared.
struct EvalSetup {
  DemoSet demos;
  vae::TrajectoryVae model{nullptr};
  std::unique_ptr<Env> env;
  std::vector<eval::NamedPolicy> policies;
};
// Throws one line naming a missing VAE checkpoint, an unreadable file or a mismatched model.
EvalSetup load_eval_setup(const EvalInputs& inputs, torch::Device device);

}  // namespace vaegail::cli
