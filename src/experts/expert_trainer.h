// Trains one expert with PPO on its task's reward (the walker's target speed, the humanoid's
// style; ExpertSpec::task names the registry's task), in a run directory that a killed run
// resumes from:
//   run_dir/spec.json      the ExpertSpec
//   run_dir/options.json   the training options
//   run_dir/agent.pt       policy, critic and observation normaliser, and the run's state
//                          ("state": state.json's JSON) they were saved in (written atomically)
//   run_dir/state.json     iteration, steps, done, seconds (written atomically after agent.pt)
//   run_dir/metrics.csv    one row per iteration
// A resumed run goes by the state agent.pt holds, and drops the metrics rows past it. It is not
// the uninterrupted run: its environments start new episodes, its Adam moments start from zero
// and its streams restart from the iteration count (reproducibly).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "env/env.h"
#include "experts/expert_spec.h"
#include "rl/agent.h"
#include "rl/ppo.h"

namespace vaegail {

struct ExpertTrainOptions {
  std::int64_t total_steps = 3000000;
  int num_envs = 16;
  int steps_per_env = 256;
  int env_threads = 1;
  std::vector<int> hidden = {64, 64};
  double gamma = 0.99;
  double lambda = 0.95;
  double learning_rate = 3e-4;
  int epochs = 10;
  int minibatches = 32;
  double target_kl = 0.02;
  int checkpoint_every = 5;  // iterations
  std::string device = "cpu";
  double posture_cost = 0.0;  // walker only: WalkerOptions::posture_cost of the training reward (0: the published experts')
};

// options.json (and a config file's "training"): every field under its own name; a missing key
// takes the struct's default.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(ExpertTrainOptions, total_steps, num_envs, steps_per_env, env_threads,
                                                hidden, gamma, lambda, learning_rate, epochs, minibatches, target_kl,
                                                checkpoint_every, device, posture_cost)

// The environment an expert trains in, in its spec's first context: the registry's task, with
// the walker's posture cost (throws for a posture cost on another task).
std::unique_ptr<Env> make_expert_env(const ExpertSpec& spec, double posture_cost = 0.0);

std::shared_ptr<Agent> make_expert_agent(const ExpertSpec& spec, const ExpertTrainOptions& options,
                                         int obs_dim, int act_dim);

// Trains until options.total_steps, resuming whatever run_dir holds; returns at once if the
// run is done. progress(steps_done) is called after every iteration.
void train_expert(const ExpertSpec& spec, const ExpertTrainOptions& options, const std::string& run_dir,
                  const std::function<void(std::int64_t)>& progress = nullptr);

struct LoadedExpert {
  ExpertSpec spec;
  ExpertTrainOptions options;
  std::shared_ptr<Agent> agent;
};
// Throws naming the directory and the missing or malformed file.
LoadedExpert load_expert(const std::string& run_dir);
bool expert_done(const std::string& run_dir);
// Environment steps trained so far (0 for a run that has not started).
std::int64_t expert_steps(const std::string& run_dir);

}  // namespace vaegail
