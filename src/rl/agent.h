// Policy, critic and observation normaliser as one unit: what a rollout runs, what an update
// trains and what a checkpoint holds.
//
// The networks' input is normalise(observation) ++ condition, [B, obs_dim + condition_dim];
// the condition is the per-episode vector (target speed for experts, latent z for GAIL).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rl/critic.h"
#include "rl/gaussian_policy.h"
#include "rl/obs_normalizer.h"

namespace vaegail {

struct AgentOptions {
  int obs_dim = 0;
  int condition_dim = 0;
  int act_dim = 0;
  std::vector<int> policy_hidden = {200, 100};
  std::vector<int> critic_hidden = {200, 100};
  Activation activation = Activation::Tanh;
  double init_log_std = -1.0;
  double obs_clip = 10.0;
};

class Agent : public torch::nn::Module {
 public:
  // Takes any policy (e.g. GAIL's residual one); input sizes must agree.
  Agent(std::shared_ptr<StochasticPolicy> policy, std::shared_ptr<Critic> critic,
        std::shared_ptr<ObsNormalizer> normalizer);
  // A GaussianPolicy agent on the CPU; call ->to(device) to move it.
  static std::shared_ptr<Agent> make_gaussian(const AgentOptions& options);

  StochasticPolicy& policy() { return *policy_; }
  Critic& critic() { return *critic_; }
  ObsNormalizer& normalizer() { return *normalizer_; }
  std::shared_ptr<StochasticPolicy> policy_ptr() const { return policy_; }
  std::shared_ptr<Critic> critic_ptr() const { return critic_; }

  int obs_dim() const { return normalizer_->dim(); }
  int condition_dim() const { return policy_->input_dim() - normalizer_->dim(); }
  int act_dim() const { return policy_->act_dim(); }
  torch::Device device() const;

  // observations [B, obs_dim] (raw), conditions [B, condition_dim] → [B, input_dim] on
  // the agent's device.
  torch::Tensor input(const torch::Tensor& observations, const torch::Tensor& conditions) const;

  // The whole agent (parameters and normaliser statistics). save() writes a temporary file
  // and renames it, so a crash never leaves a half checkpoint; load() needs an agent of the
  // same architecture and keeps its device.
  void save_checkpoint(const std::string& path) const;
  void load_checkpoint(const std::string& path);

 private:
  std::shared_ptr<StochasticPolicy> policy_;
  std::shared_ptr<Critic> critic_;
  std::shared_ptr<ObsNormalizer> normalizer_;
};

}  // namespace vaegail
