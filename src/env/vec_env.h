// N environments stepped together on a thread pool.
//
// Buffers are row-major: observations [N, obs_dim], actions [N, act_dim], rewards [N].
// Each environment owns its seed stream: environment i is reset with seeds[i], and when
// auto-reset is on, its k-th following episode starts from derive_seed(seeds[i], k). Nothing
// depends on N or on the thread count, so an environment's trajectory is bit-identical
// whatever the pool looks like.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "env/env.h"
#include "util/thread_pool.h"

namespace vaegail {

class VecEnv {
 public:
  VecEnv(const Env& prototype, int num_envs, int num_threads = 1);

  int size() const { return static_cast<int>(envs_.size()); }
  int obs_dim() const { return obs_dim_; }
  int act_dim() const { return act_dim_; }
  Env& env(int i) { return *envs_[i]; }
  const Env& env(int i) const { return *envs_[i]; }

  // After an environment finishes an episode, start its next one in the same step() call;
  // observations() then holds the new episode's first observation and final_observations()
  // the finished episode's last one.
  void set_auto_reset(bool on) { auto_reset_ = on; }

  void reset(const std::vector<std::uint64_t>& seeds);
  void step(const float* actions);

  // The pool's contiguous blocks of environments, fn(first, count) for each, one block per
  // thread: a caller that also computes per environment (a policy's forward pass) runs it beside
  // the physics of its block, on every core, instead of serially before step().
  void for_each_block(const std::function<void(int first, int count)>& fn);
  // step() for environments [first, first + count) only; `actions` holds their rows.
  void step_block(int first, int count, const float* actions);

  const std::vector<float>& observations() const { return obs_; }
  const std::vector<float>& final_observations() const { return final_obs_; }
  const std::vector<float>& rewards() const { return rewards_; }
  // 0/1 per environment for the step just taken.
  const std::vector<std::uint8_t>& terminated() const { return terminated_; }
  const std::vector<std::uint8_t>& truncated() const { return truncated_; }
  // Episodes started by environment i since reset() (0 for the first).
  int episode_index(int i) const { return episode_index_[i]; }

 private:
  void step_one(int i, const float* action);

  std::vector<std::unique_ptr<Env>> envs_;
  ThreadPool pool_;
  int obs_dim_, act_dim_;
  bool auto_reset_ = false;
  std::vector<std::uint64_t> seeds_;
  std::vector<int> episode_index_;
  std::vector<float> obs_, final_obs_, rewards_;
  std::vector<std::uint8_t> terminated_, truncated_;
};

}  // namespace vaegail
