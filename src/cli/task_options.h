// Flags shared by the commands that build an environment.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include <torch/torch.h>

#include "data/demos.h"
#include "env/registry.h"
#include "vae/latent_refinement.h"
#include "vae/trajectory_vae.h"

namespace vaegail::cli {

struct TaskOptions {
  std::string task = "walker";
  int episode_length = 0;
  int frame_skip = 0;
  bool keep_going_after_fall = false;

  EnvRequest request() const;
  std::unique_ptr<Env> make() const { return make_env(request()); }
};

// The published walker artefacts, the defaults of the commands that start from them.
inline const std::string kPublishedWalkerDemos = "data/walker/demos.h5";
inline const std::string kPublishedWalkerVae = "checkpoints/walker/vae/checkpoints/latest.pt";

// The humanoid's artefacts (paper section 4.3), where scripts/reproduce/humanoid.sh makes them:
// demonstrations of the training and evaluation controllers and the VAE run (its directory: a
// clone has the committed weights.pt, a training machine its checkpoint too).
inline const std::string kHumanoidTrainDemos = "data/humanoid/train.h5";
inline const std::string kHumanoidEvalDemos = "data/humanoid/eval.h5";
inline const std::string kHumanoidVae = "checkpoints/humanoid/vae";

// The published demonstrations are not committed (docs/artefacts.md): when `demos` names them and
// the checkout lacks them, they are made first from the committed experts by the command of
// scripts/reproduce/walker.sh's `demos` stage (byte-identical on a rerun, under a minute), echoed
// as a user would type it. Any other path is left to the command that reads it.
void ensure_published_walker_demos(const std::string& demos);

// "cpu" or "cuda"; throws (one line) if CUDA is asked for and this LibTorch has none.
torch::Device parse_device(const std::string& name);
// --device, restricted to cpu and cuda.
CLI::Option* add_device_option(CLI::App& command, std::string& device,
                               const std::string& description = "where the networks run (cpu, cuda)");

// --refine-steps (which demonstrations' z it moves is the command's to say in `whose`) and
// --refine-lr; returns --refine-steps, for exclusions.
CLI::Option* add_refine_options(CLI::App& command, vae::RefineOptions& refine, const std::string& whose);

// The environment the demonstrations were recorded in, with episodes as long as the longest: a
// built-in task by name, or a user's body from the MJCF text the file stores (with the file's
// control step and context names). Throws (one line) when the file names neither.
EnvRequest demo_env_request(const DemoSet& demos);
inline std::unique_ptr<Env> demo_env(const DemoSet& demos) { return make_env(demo_env_request(demos)); }
// The same, checked against the VAE's state and action dimensions (one-line error otherwise).
std::unique_ptr<Env> demo_env(const DemoSet& demos, const vae::TrajectoryVae& model);
// Throws (one line) when `task` is given and is not what the demonstrations were recorded on:
// another built-in task, or an MJCF file whose text differs from the stored body's (SHA-256).
void check_demo_task(const DemoSet& demos, const std::string& task);
// --task on commands that read demonstrations: checked by check_demo_task.
void add_demo_task_option(CLI::App& command, std::string& task);

}  // namespace vaegail::cli
