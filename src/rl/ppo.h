// Proximal policy optimisation (Schulman et al. 2017), the clipped-surrogate alternative to
// TRPO: several epochs of Adam minibatch steps on policy and critic together.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "rl/critic.h"
#include "rl/stochastic_policy.h"
#include "rl/update_batch.h"

namespace vaegail {

struct PpoOptions {
  double clip = 0.2;  // the probability ratio is clipped to [1 − clip, 1 + clip]
  int epochs = 10;
  int minibatches = 32;
  double learning_rate = 3e-4;
  double value_coef = 0.5;
  double entropy_coef = 0.0;
  double max_grad_norm = 0.5;
  double target_kl = 0.0;  // > 0: stop after an epoch whose mean approximate KL exceeds 1.5·target_kl
  std::uint64_t seed = 0;  // minibatch shuffling
};

// Means over the minibatch steps taken.
struct PpoStats {
  double policy_loss = 0.0;
  double value_loss = 0.0;
  double entropy = 0.0;
  double approx_kl = 0.0;      // E[(r − 1) − log r], r the probability ratio
  double clip_fraction = 0.0;  // share of samples whose ratio was clipped
  int minibatch_steps = 0;
  bool stopped_early = false;  // the target-KL stop fired
};

class Ppo {
 public:
  Ppo(std::shared_ptr<StochasticPolicy> policy, std::shared_ptr<Critic> critic, PpoOptions options = {});
  PpoStats update(const UpdateBatch& batch);

 private:
  std::shared_ptr<StochasticPolicy> policy_;
  std::shared_ptr<Critic> critic_;
  PpoOptions options_;
  std::vector<torch::Tensor> parameters_;
  torch::optim::Adam optimizer_;
  torch::Generator generator_;
};

}  // namespace vaegail
