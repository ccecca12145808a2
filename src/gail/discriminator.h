// The GAIL discriminator D_ψ(x, a | z) of paper section 3.2: an MLP on [state features,
// action, z] → logit, D = sigmoid(logit); D → 1 on demonstrations, → 0 on the policy.
//
// Shapes: observations [B, obs_dim] raw, actions [B, act_dim] raw, z [B, latent_dim]
// (latent_dim 0: the unconditional discriminator of plain GAIL; z is then ignored).
//
// Input: the selected state components (all by default; the paper feeds the humanoid's
// discriminator a subset, mostly end-effector positions) and the action clipped to the
// environment's bounds, both standardised with the demonstrations' mean and std. The bounds
// and statistics are buffers, so a checkpoint is self-contained. Clipping matters: demos and
// the policy record actions before the environment clips them, and a discriminator that can
// tell them apart by |a| > 1 alone would teach the policy nothing about behaviour.
#pragma once

#include <torch/torch.h>

#include <memory>
#include <vector>

#include "rl/distributed.h"
#include "rl/mlp.h"

namespace vaegail {

struct DiscriminatorOptions {
  int obs_dim = 0;
  int act_dim = 0;
  int latent_dim = 0;               // 0: unconditional
  std::vector<int> state_indices;   // the observation components it sees; empty: all
  std::vector<double> action_low, action_high;  // empty: actions are not clipped
  std::vector<int> hidden = {100, 64};  // Table 2, walker
  Activation activation = Activation::Tanh;
};

// (x, a, z) samples of one side of the game; z [B, 0] for the unconditional discriminator.
struct DiscriminatorData {
  torch::Tensor observations, actions, z;
  int64_t size() const { return observations.size(0); }
};

class Discriminator : public torch::nn::Module {
 public:
  explicit Discriminator(const DiscriminatorOptions& options);

  // Standardisation statistics of the (x, a) the discriminator sees, from the demonstrations:
  // observations [M, obs_dim], actions [M, act_dim].
  void fit_normalization(const torch::Tensor& observations, const torch::Tensor& actions);

  // → logits [B]
  torch::Tensor forward(const torch::Tensor& observations, const torch::Tensor& actions, const torch::Tensor& z);
  torch::Tensor forward(const DiscriminatorData& data) { return forward(data.observations, data.actions, data.z); }

  int latent_dim() const { return latent_dim_; }
  int obs_dim() const { return obs_dim_; }
  int act_dim() const { return act_dim_; }

 private:
  // [B, obs_dim], [B, act_dim] → selected state ++ clipped action, [B, feature_dim], unnormalised.
  torch::Tensor features(const torch::Tensor& observations, const torch::Tensor& actions) const;

  int obs_dim_, act_dim_, latent_dim_;
  torch::Tensor state_indices_, action_low_, action_high_, feature_mean_, feature_std_;
  std::shared_ptr<Mlp> net_;
};

struct DiscriminatorStats {
  double loss = 0.0;             // binary cross-entropy: mean over demos + mean over the policy
  double demo_accuracy = 0.0;    // fraction of demonstration samples with D > 1/2
  double policy_accuracy = 0.0;  // fraction of policy samples with D < 1/2
};

// The loss and accuracies on both sides, without gradient. `global_count`: where these pairs are
// one rank's share of a run's (rl/distributed.h), how many pairs the run has (0: these are all).
DiscriminatorStats evaluate_discriminator(Discriminator& discriminator, const DiscriminatorData& demos,
                                          const DiscriminatorData& policy, int64_t global_count = 0);

// Adam on the binary cross-entropy, demonstrations labelled 1, policy samples 0; each side
// averaged on its own so that their sizes do not set the balance (Algorithm 1's gradient).
class DiscriminatorTrainer {
 public:
  DiscriminatorTrainer(std::shared_ptr<Discriminator> discriminator, double learning_rate = 1e-4);

  // `steps` Adam steps (Table 3: 10 per iteration), each on 1/`minibatches` of both sides'
  // samples, taken in turn from one shuffle drawn from `generator` (minibatches 1: every step on
  // the whole batch). The paper gives the step count, not the batch: steps = minibatches is one
  // pass over the iteration's data, as OpenAI baselines' GAIL takes it, at a tenth of the
  // full-batch cost. The stats are those of the discriminator as it was before the first step,
  // on all the samples: how well it told this fresh data apart. `rows`: where the pairs are one
  // rank's share of the run's (rl/distributed.h), their global rows; the shuffle is then drawn
  // over the run's pairs and gradients are summed over the ranks (default: these are all).
  DiscriminatorStats train(const DiscriminatorData& demos, const DiscriminatorData& policy, int steps,
                           int minibatches, at::Generator& generator, const RowSlice& rows = {});

  torch::optim::Adam& optimizer() { return optimizer_; }

 private:
  std::shared_ptr<Discriminator> discriminator_;
  torch::optim::Adam optimizer_;
};

}  // namespace vaegail
