// The behaviour-cloning baseline: a Gaussian MLP policy π(a | x) (no latent) fitted by
// maximum likelihood to every (x, a) step of the training demonstrations pooled together,
// the "BC" the paper's diverse policies are compared against.
//
// The result is an Agent (GaussianPolicy, observation normaliser frozen at the
// demonstrations' statistics, and an untrained linear critic the Agent type requires), so
// the rl and eval tools run it like any other policy.
//
// Run directory:
//   run_dir/config.json             BcOptions
//   run_dir/metrics.csv             epoch, train_nll, val_nll (NaN without held-out episodes), seconds
//   run_dir/checkpoints/latest.pt   agent, Adam state, epoch (atomic, after every epoch)
// Epoch e shuffles with a stream derived from (seed, e), so a resumed run equals the
// uninterrupted one.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "data/demos.h"
#include "gail/bc_agent.h"
#include "rl/agent.h"

namespace vaegail {

class BehaviorCloning {
 public:
  // observations [M, obs_dim], actions [M, act_dim] (CPU or device).
  BehaviorCloning(const torch::Tensor& observations, const torch::Tensor& actions, BcOptions options);

  // One pass of shuffled minibatches; returns the mean negative log-likelihood of the epoch.
  double train_epoch();
  // Mean -log π(a | x) over the pairs, without gradient.
  double nll(const torch::Tensor& observations, const torch::Tensor& actions);

  void save_checkpoint(const std::string& path) const;
  void load_checkpoint(const std::string& path);

  int epoch() const { return epoch_; }
  Agent& agent() { return *agent_; }

 private:
  torch::Tensor negative_log_likelihood(const torch::Tensor& observations, const torch::Tensor& actions);

  BcOptions options_;
  torch::Tensor observations_, actions_;
  std::shared_ptr<Agent> agent_;
  std::unique_ptr<torch::optim::Adam> optimizer_;
  int epoch_ = 0;
};

struct BcEpoch {
  int epoch = 0;
  double train_nll = 0, val_nll = 0, seconds = 0;
};

// Trains on the demonstrations' training split (vae/demo_dataset.h's split_demos: the
// held-out episodes, or a seeded 10%, validate) until options.epochs, resuming run_dir, which it
// holds meanwhile (util/run_lock.h: a second trainer on it is refused).
void train_bc(const DemoSet& demos, const BcOptions& options, const std::string& run_dir,
              const std::function<void(const BcEpoch&)>& on_epoch = nullptr);

}  // namespace vaegail
