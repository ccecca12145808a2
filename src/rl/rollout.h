// On-policy data collection: run the agent's policy in a VecEnv for a fixed number of steps
// per environment, episodes continuing across collect() calls.
//
// Every tensor in a Rollout is float32 on the agent's device, time-major:
//   observations [T, N, obs_dim]    raw observation before each step
//   conditions   [T, N, cond_dim]   the episode's condition at each step
//   inputs       [T, N, input_dim]  what the networks saw: normalise(obs) ++ condition
//   actions      [T, N, act_dim]    sampled actions, before the environment clips them
//   log_probs, values, env_rewards, rewards, terminated, truncated, next_values   [T, N]
// terminated/truncated are 0/1. next_values[t] is V of the state reached by step t: the next
// step's value, V(final observation) where the step truncated an episode (the time limit is
// not part of the task, so the return is bootstrapped), and 0 where it terminated one.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "env/vec_env.h"
#include "rl/agent.h"
#include "rl/distributed.h"

namespace vaegail {

struct EpisodeRecord {
  int env_index = 0;
  double env_return = 0.0;  // sum of environment rewards over the whole episode
  int length = 0;
  bool terminated = false;  // false: ended by the time limit
  std::vector<float> condition;
};

struct Rollout {
  torch::Tensor observations, conditions, inputs, actions;
  torch::Tensor log_probs, values, next_values;
  torch::Tensor env_rewards, rewards;
  torch::Tensor terminated, truncated;
  // Episodes that ended during this collection (they may have begun in an earlier one).
  std::vector<EpisodeRecord> episodes;
};

// Where the rewards that train the policy come from. Called once per collection, after all
// steps are stored; returns [T, N]. GAIL plugs its discriminator in here.
class RewardSource {
 public:
  virtual ~RewardSource() = default;
  virtual torch::Tensor rewards(const Rollout& rollout) = 0;
};

// The default: the environment's own reward.
class EnvReward : public RewardSource {
 public:
  torch::Tensor rewards(const Rollout& rollout) override { return rollout.env_rewards; }
};

// Called for environment env_index just before each of its episodes starts, in environment
// order. It may set the environment's context (e.g. a target speed) and returns the episode's
// condition, condition_dim values.
using EpisodeStartFn = std::function<std::vector<float>(int env_index, Env& env)>;

class RolloutCollector {
 public:
  // On the first collect() the collector switches `envs` to auto-reset, calls the hook for
  // every environment and resets them all; it owns their episodes from then on. Environment i
  // gets seed stream i of `seed`. Without a hook, the agent's condition_dim must be 0.
  // `slice`: which of a run's environments `envs` are when ranks share them (rl/distributed.h):
  // environment i is then the run's first + i, with that seed stream and that column of the
  // action noise, so the ranks' rollouts together are the one-process rollout of the run. The
  // default: all of them.
  RolloutCollector(VecEnv& envs, std::shared_ptr<Agent> agent, std::uint64_t seed,
                   EpisodeStartFn on_episode_start = nullptr,
                   std::shared_ptr<RewardSource> reward_source = std::make_shared<EnvReward>(),
                   EnvSlice slice = {});

  // Runs steps_per_env steps in every environment. Afterwards the agent's normaliser (unless
  // frozen) has absorbed the run's rollout's observations (all ranks'), for the next collection.
  Rollout collect(int steps_per_env);

 private:
  void start();
  void begin_episode(int i);
  torch::Tensor current_observations() const;
  torch::Tensor current_conditions() const;

  VecEnv& envs_;
  std::shared_ptr<Agent> agent_;
  EpisodeStartFn on_episode_start_;
  std::shared_ptr<RewardSource> reward_source_;
  EnvSlice slice_;
  std::vector<std::uint64_t> seeds_;
  torch::Generator generator_;
  bool started_ = false;
  int obs_dim_, cond_dim_;
  // Kept here rather than read from envs_: the hook may re-reset an environment.
  std::vector<float> obs_, conditions_;
  std::vector<EpisodeRecord> running_;
};

}  // namespace vaegail
