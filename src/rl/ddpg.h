// Deep deterministic policy gradient (Lillicrap et al. 2016), the learner the paper's appendix
// uses for the arm's reaching experts: a deterministic actor μ(s), a critic Q(s, a), slowly
// tracking target copies of both, a replay buffer, and Gaussian exploration noise.
//
//   critic:  minimise (Q(s, a) - y)^2,  y = r + γ (1 - terminated) Q'(s', μ'(s'))
//   actor:   maximise Q(s, μ(s)) - λ mean(u²), u the actor's output before tanh: the penalty
//            keeps the actor out of tanh's saturated tails, where a stuck actor cannot recover
//   targets: θ' ← τ θ + (1 - τ) θ'
// Truncation by the time limit is not termination: the target still bootstraps there.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "env/env.h"
#include "rl/mlp.h"

namespace vaegail {

// Transitions (s, a, r, s', terminated) in a ring of fixed capacity: the oldest go first.
class ReplayBuffer {
 public:
  ReplayBuffer(int obs_dim, int act_dim, int64_t capacity);
  void add(const float* obs, const float* action, double reward, const float* next_obs, bool terminated);
  int64_t size() const { return size_; }

  struct Batch {
    torch::Tensor obs, actions, rewards, next_obs, terminated;  // [B, ·], rewards/terminated [B]
  };
  // `batch` transitions drawn uniformly with replacement.
  Batch sample(int batch, torch::Generator& generator) const;

 private:
  int obs_dim_, act_dim_;
  int64_t capacity_, size_ = 0, next_ = 0;
  torch::Tensor obs_, actions_, rewards_, next_obs_, terminated_;
};

// y = r + γ (1 - terminated) q_next, elementwise.
torch::Tensor td_target(const torch::Tensor& rewards, const torch::Tensor& terminated, const torch::Tensor& q_next,
                        double gamma);

// target ← τ source + (1 - τ) target, parameter by parameter (τ = 1 copies).
void soft_update(torch::nn::Module& target, const torch::nn::Module& source, double tau);

struct DdpgOptions {
  std::vector<int> actor_hidden = {64, 64};
  std::vector<int> critic_hidden = {64, 64};
  double actor_learning_rate = 1e-3;
  double critic_learning_rate = 1e-3;
  double gamma = 0.99;
  double tau = 0.005;
  int batch_size = 64;
  int64_t buffer_capacity = 1000000;
  double exploration_std = 0.2;  // Gaussian noise on the actor's action, in action units
  int warmup_steps = 500;        // uniform random actions before the actor takes over
  double pre_activation_penalty = 1e-3;  // λ above
  std::uint64_t seed = 0;
};

struct DdpgStats {
  double critic_loss = 0, actor_objective = 0;  // mean Q(s, μ(s)) on the batch
};

class Ddpg {
 public:
  // Actions are squashed by tanh into the environment's action box.
  Ddpg(int obs_dim, const BoxSpec& action_spec, DdpgOptions options = {});

  // μ(s) [B, act_dim] for observations [B, obs_dim].
  torch::Tensor act(const torch::Tensor& obs);
  // Q(s, a) [B].
  torch::Tensor q(const torch::Tensor& obs, const torch::Tensor& actions);
  // The critic's regression targets for a batch, from the target networks.
  torch::Tensor critic_targets(const ReplayBuffer::Batch& batch);
  // One critic step, one actor step, one target update.
  DdpgStats update(const ReplayBuffer::Batch& batch);

  // Runs the environment for `steps` control steps from a fresh episode (warm-up until
  // warmup_steps have been taken over all calls, then the noisy actor), storing every
  // transition and updating once per step once the buffer holds a batch. Returns the last
  // update's statistics (zeros if none ran).
  DdpgStats train(Env& env, int64_t steps);
  int64_t steps_trained() const { return steps_trained_; }
  // Mean return of `episodes` noise-free episodes, seeds base_seed, base_seed + 1, ...
  double evaluate(const Env& env, int episodes, std::uint64_t base_seed);

  // The actor alone: what a trained expert needs to act (written atomically).
  void save_actor(const std::string& path);
  void load_actor(const std::string& path);

  ReplayBuffer& buffer() { return buffer_; }
  Mlp& actor() { return *actor_; }
  Mlp& critic() { return *critic_; }
  Mlp& target_actor() { return *target_actor_; }
  Mlp& target_critic() { return *target_critic_; }

 private:
  torch::Tensor squash(const torch::Tensor& pre_activation) const;
  std::vector<float> explore(const std::vector<float>& obs, int64_t step);

  DdpgOptions options_;
  torch::Tensor low_, high_;
  std::shared_ptr<Mlp> actor_, critic_, target_actor_, target_critic_;
  std::unique_ptr<torch::optim::Adam> actor_optimizer_, critic_optimizer_;
  ReplayBuffer buffer_;
  torch::Generator generator_;
  std::uint64_t episode_seed_ = 0;
  int64_t steps_trained_ = 0;
};

}  // namespace vaegail
