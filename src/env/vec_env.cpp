#include "env/vec_env.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "util/rng.h"

namespace vaegail {

VecEnv::VecEnv(const Env& prototype, int num_envs, int num_threads)
    : pool_(std::min(num_threads, std::max(num_envs, 1))),
      obs_dim_(prototype.obs_dim()), act_dim_(prototype.act_dim()) {
  if (num_envs < 1) throw std::invalid_argument("VecEnv needs at least one environment");
  for (int i = 0; i < num_envs; ++i) envs_.push_back(prototype.clone());
  seeds_.assign(num_envs, 0);
  episode_index_.assign(num_envs, 0);
  obs_.assign(static_cast<size_t>(num_envs) * obs_dim_, 0.f);
  final_obs_ = obs_;
  rewards_.assign(num_envs, 0.f);
  terminated_.assign(num_envs, 0);
  truncated_.assign(num_envs, 0);
}

void VecEnv::reset(const std::vector<std::uint64_t>& seeds) {
  if (static_cast<int>(seeds.size()) != size())
    throw std::invalid_argument("VecEnv::reset: " + std::to_string(seeds.size()) + " seeds for " +
                                std::to_string(size()) + " environments");
  seeds_ = seeds;
  pool_.parallel_for(size(), [&](int i) {
    episode_index_[i] = 0;
    envs_[i]->reset(seeds_[i]);
    envs_[i]->observe(&obs_[static_cast<size_t>(i) * obs_dim_]);
    terminated_[i] = truncated_[i] = 0;
    rewards_[i] = 0.f;
  });
}

void VecEnv::step_one(int i, const float* action) {
  Env& env = *envs_[i];
  const StepOutcome out = env.step(action);
  float* obs = &obs_[static_cast<size_t>(i) * obs_dim_];
  env.observe(obs);
  rewards_[i] = static_cast<float>(out.reward);
  terminated_[i] = out.terminated;
  truncated_[i] = out.truncated;
  if (auto_reset_ && out.done()) {
    std::copy(obs, obs + obs_dim_, &final_obs_[static_cast<size_t>(i) * obs_dim_]);
    ++episode_index_[i];
    env.reset(derive_seed(seeds_[i], static_cast<std::uint64_t>(episode_index_[i])));
    env.observe(obs);
  }
}

void VecEnv::step(const float* actions) {
  pool_.parallel_for(size(), [&](int i) { step_one(i, actions + static_cast<size_t>(i) * act_dim_); });
}

void VecEnv::for_each_block(const std::function<void(int first, int count)>& fn) {
  const int blocks = pool_.size();
  pool_.parallel_for(blocks, [&](int b) {
    const int first = size() * b / blocks, end = size() * (b + 1) / blocks;
    if (end > first) fn(first, end - first);
  });
}

void VecEnv::step_block(int first, int count, const float* actions) {
  if (first < 0 || count < 0 || first + count > size())
    throw std::out_of_range("VecEnv::step_block: environments [" + std::to_string(first) + ", " +
                            std::to_string(first + count) + ") of " + std::to_string(size()));
  for (int i = first; i < first + count; ++i) step_one(i, actions + static_cast<size_t>(i - first) * act_dim_);
}

}  // namespace vaegail
