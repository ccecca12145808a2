// Trust region policy optimisation (Schulman et al. 2015), the policy update the paper uses
// for the experts and for GAIL: one natural-gradient step per batch on the importance-sampled
// surrogate, its length set by a bound on the mean KL(old ‖ new), then a backtracking line
// search that keeps the step only if the surrogate improves within the bound. The critic is
// fitted separately, by Adam minibatches on the GAE returns.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "rl/critic.h"
#include "rl/stochastic_policy.h"
#include "rl/update_batch.h"

namespace vaegail {

struct TrpoOptions {
  double max_kl = 0.01;
  int cg_iterations = 10;
  double cg_damping = 0.1;  // F + damping·I: keeps CG well posed where the batch barely constrains F
  // Fisher-vector products on every k-th sample of the batch (OpenAI baselines' TRPO uses 5): the
  // curvature estimate needs far fewer samples than the gradient, and CG runs ten of them.
  int fisher_stride = 5;
  int line_search_steps = 10;
  double backtrack_ratio = 0.5;
  double entropy_coef = 0.0;
  int critic_epochs = 5;
  int critic_minibatches = 16;
  double critic_learning_rate = 1e-3;
  std::uint64_t seed = 0;  // minibatch shuffling
};

struct TrpoStats {
  double surrogate_improvement = 0.0;  // surrogate after − before, on the batch
  double expected_improvement = 0.0;   // the linear prediction for the full step
  double kl = 0.0;                     // mean KL(old ‖ new) of the kept step
  double entropy = 0.0;                // mean policy entropy after the step
  int line_search_steps = 0;           // halvings before the step was kept
  bool accepted = false;               // false: no candidate passed, the policy is unchanged
  double value_loss_before = 0.0;      // critic MSE on the batch before and after fitting
  double value_loss_after = 0.0;
};

// Every mean over the batch is over the run's batch (UpdateBatch::global_size): with the batch
// spread over ranks, each rank sums its rows and the sums are added over the ranks
// (rl/distributed.h), so every rank takes the same step.
//
// One Trpo serves a whole training run: the critic's Adam state carries over between updates
// (a checkpoint saves critic_optimizer()); reseed() gives each update its own shuffling stream.
class Trpo {
 public:
  Trpo(std::shared_ptr<StochasticPolicy> policy, std::shared_ptr<Critic> critic, TrpoOptions options = {});
  TrpoStats update(const UpdateBatch& batch);
  void reseed(std::uint64_t seed);
  torch::optim::Adam& critic_optimizer() { return critic_optimizer_; }

 private:
  void step_policy(const UpdateBatch& batch, const torch::Tensor& frozen, TrpoStats& stats);
  void fit_critic(const UpdateBatch& batch, TrpoStats& stats);

  std::shared_ptr<StochasticPolicy> policy_;
  std::shared_ptr<Critic> critic_;
  TrpoOptions options_;
  torch::optim::Adam critic_optimizer_;
  torch::Generator generator_;
};

// v ↦ A·v for a flat vector v.
using LinearOperator = std::function<torch::Tensor(const torch::Tensor&)>;

// v ↦ (F + damping·I)·v, F the Fisher matrix of the policy's trainable parameters at their
// current values on `inputs`: the Hessian of the mean KL(π_current ‖ π_θ), by double backprop.
// `frozen` is policy.frozen_mean(inputs) (undefined where the policy has none). Where the
// inputs are one rank's share of a run's `global_count` rows (rl/distributed.h), F is the mean
// over all of them, summed over the ranks; 0: the inputs are all there is.
// The operator is only valid while the parameters keep their current values.
LinearOperator fisher_vector_product(StochasticPolicy& policy, const torch::Tensor& inputs,
                                     const torch::Tensor& frozen, double damping, int64_t global_count = 0);

// Solves A·x = b for symmetric positive definite A, from x = 0, in at most `iterations` steps
// (earlier once the squared residual falls below residual_tol).
torch::Tensor conjugate_gradient(const LinearOperator& A, const torch::Tensor& b, int iterations,
                                 double residual_tol = 1e-10);

}  // namespace vaegail
