#include "rl/rollout.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "util/rng.h"

namespace vaegail {

namespace {

// A CPU tensor copied out of a row-major buffer; float32 whatever the buffer holds.
template <typename T>
torch::Tensor copy_buffer(const std::vector<T>& buffer, torch::IntArrayRef shape, torch::Dtype buffer_dtype) {
  if (buffer.empty()) return torch::zeros(shape);
  return torch::from_blob(const_cast<T*>(buffer.data()), shape, buffer_dtype).to(torch::kFloat32, false, true);
}

// Rows [first, first + count) of a row-major [*, dim] buffer, as a CPU tensor of its own.
torch::Tensor buffer_rows(const std::vector<float>& buffer, int first, int count, int dim) {
  if (dim == 0) return torch::zeros({count, 0});
  return torch::from_blob(const_cast<float*>(buffer.data()) + static_cast<size_t>(first) * dim, {count, dim}).clone();
}

}  // namespace

RolloutCollector::RolloutCollector(VecEnv& envs, std::shared_ptr<Agent> agent, std::uint64_t seed,
                                   EpisodeStartFn on_episode_start, std::shared_ptr<RewardSource> reward_source,
                                   EnvSlice slice)
    : envs_(envs),
      agent_(std::move(agent)),
      on_episode_start_(std::move(on_episode_start)),
      reward_source_(std::move(reward_source)),
      slice_(slice.total > 0 ? slice : EnvSlice::whole(envs.size())),
      // The run's environment e uses stream e of the seed; the action noise the stream after them.
      generator_(at::detail::createCPUGenerator(derive_seed(seed, slice_.total))),
      obs_dim_(envs.obs_dim()),
      cond_dim_(agent_->condition_dim()) {
  if (envs.obs_dim() != agent_->obs_dim() || envs.act_dim() != agent_->act_dim())
    throw std::invalid_argument("RolloutCollector: environment (obs " + std::to_string(envs.obs_dim()) + ", act " +
                                std::to_string(envs.act_dim()) + ") does not fit the agent (obs " +
                                std::to_string(agent_->obs_dim()) + ", act " + std::to_string(agent_->act_dim()) +
                                ")");
  if (cond_dim_ > 0 && !on_episode_start_)
    throw std::invalid_argument("RolloutCollector: the agent takes a condition but no episode-start hook gives one");
  if (slice_.count != envs.size())
    throw std::invalid_argument("RolloutCollector: a slice of " + std::to_string(slice_.count) + " environments, " +
                                std::to_string(envs.size()) + " given");
  for (int i = 0; i < envs.size(); ++i) seeds_.push_back(derive_seed(seed, slice_.first + i));
  obs_.assign(static_cast<size_t>(envs.size()) * obs_dim_, 0.f);
  conditions_.assign(static_cast<size_t>(envs.size()) * cond_dim_, 0.f);
  running_.resize(envs.size());
}

void RolloutCollector::begin_episode(int i) {
  running_[i] = EpisodeRecord{};
  running_[i].env_index = i;
  if (!on_episode_start_) return;
  auto condition = on_episode_start_(i, envs_.env(i));
  if (static_cast<int>(condition.size()) != cond_dim_)
    throw std::runtime_error("episode-start hook returned " + std::to_string(condition.size()) +
                             " condition values, the agent takes " + std::to_string(cond_dim_));
  std::copy(condition.begin(), condition.end(), conditions_.begin() + static_cast<size_t>(i) * cond_dim_);
  running_[i].condition = std::move(condition);
}

void RolloutCollector::start() {
  envs_.set_auto_reset(true);
  for (int i = 0; i < envs_.size(); ++i) begin_episode(i);
  envs_.reset(seeds_);
  obs_ = envs_.observations();
  started_ = true;
}

torch::Tensor RolloutCollector::current_observations() const {
  return copy_buffer(obs_, {envs_.size(), obs_dim_}, torch::kFloat32);
}

torch::Tensor RolloutCollector::current_conditions() const {
  return copy_buffer(conditions_, {envs_.size(), cond_dim_}, torch::kFloat32);
}

Rollout RolloutCollector::collect(int steps_per_env) {
  if (steps_per_env < 1) throw std::invalid_argument("RolloutCollector::collect: steps_per_env must be positive");
  if (!started_) start();
  torch::NoGradGuard no_grad;
  const int n = envs_.size(), act_dim = envs_.act_dim();
  const int64_t T = steps_per_env;
  const auto device = agent_->device();
  StochasticPolicy& policy = agent_->policy();
  Critic& critic = agent_->critic();

  // Filled block by block on the pool's threads; each block writes only its own columns.
  Rollout out;
  const auto cpu = torch::TensorOptions().dtype(torch::kFloat32);
  auto observations = torch::empty({T, n, obs_dim_}, cpu), conditions = torch::empty({T, n, cond_dim_}, cpu);
  auto inputs = torch::empty({T, n, agent_->obs_dim() + cond_dim_}, cpu), actions = torch::empty({T, n, act_dim}, cpu);
  auto log_probs = torch::empty({T, n}, cpu), values = torch::empty({T, n}, cpu);
  std::vector<float> rewards(static_cast<size_t>(T) * n), final_values(rewards.size(), 0.f);
  std::vector<std::uint8_t> terminated(rewards.size()), truncated(rewards.size());
  for (int64_t t = 0; t < T; ++t) {
    // Drawn for all the run's environments at once, in one stream: the same numbers whatever the
    // blocks and ranks.
    const auto noise = torch::randn({slice_.total, act_dim}, generator_).narrow(0, slice_.first, n);
    envs_.for_each_block([&](int first, int count) {
      torch::NoGradGuard block_no_grad;  // thread-local: the pool's threads need their own
      const auto rows = [&](const torch::Tensor& x) { return x.select(0, t).narrow(0, first, count); };
      const auto obs = buffer_rows(obs_, first, count, obs_dim_);
      const auto cond = buffer_rows(conditions_, first, count, cond_dim_);
      const auto input = agent_->input(obs, cond);
      const auto dist = policy.distribution(input);
      const auto action = dist.mean + torch::exp(dist.log_std) * noise.narrow(0, first, count).to(device);
      rows(observations).copy_(obs);
      rows(conditions).copy_(cond);
      rows(inputs).copy_(input);
      rows(actions).copy_(action);
      rows(log_probs).copy_(dist.log_prob(action));
      rows(values).copy_(critic.forward(input));
      const auto action_cpu = action.to(torch::kCPU).contiguous();
      envs_.step_block(first, count, action_cpu.data_ptr<float>());
      for (int i = first; i < first + count; ++i) {
        if (!envs_.truncated()[i]) continue;
        // The finished episode's condition is still in `cond`: begin_episode replaces it later.
        const auto final_obs = buffer_rows(envs_.final_observations(), i, 1, obs_dim_);
        final_values[t * n + i] = critic.forward(agent_->input(final_obs, cond.narrow(0, i - first, 1))).item<float>();
      }
    });
    std::copy(envs_.rewards().begin(), envs_.rewards().end(), rewards.begin() + t * n);
    std::copy(envs_.terminated().begin(), envs_.terminated().end(), terminated.begin() + t * n);
    std::copy(envs_.truncated().begin(), envs_.truncated().end(), truncated.begin() + t * n);

    for (int i = 0; i < n; ++i) {
      EpisodeRecord& episode = running_[i];
      episode.env_return += envs_.rewards()[i];
      ++episode.length;
      const auto row = envs_.observations().begin() + static_cast<long>(i) * obs_dim_;
      std::copy(row, row + obs_dim_, obs_.begin() + static_cast<long>(i) * obs_dim_);
      if (!envs_.terminated()[i] && !envs_.truncated()[i]) continue;
      episode.terminated = envs_.terminated()[i];
      out.episodes.push_back(std::move(episode));
      begin_episode(i);
      if (on_episode_start_) {
        // VecEnv already started the next episode, before the hook could set its context;
        // start it again from the same seed (VecEnv's scheme) now that the context is set.
        Env& env = envs_.env(i);
        env.reset(derive_seed(seeds_[i], static_cast<std::uint64_t>(envs_.episode_index(i))));
        env.observe(&obs_[static_cast<size_t>(i) * obs_dim_]);
      }
    }
  }

  out.observations = observations.to(device);
  out.conditions = conditions.to(device);
  out.inputs = inputs.to(device);
  out.actions = actions.to(device);
  out.log_probs = log_probs.to(device);
  out.values = values.to(device);
  out.env_rewards = copy_buffer(rewards, {T, n}, torch::kFloat32).to(device);
  out.terminated = copy_buffer(terminated, {T, n}, torch::kUInt8).to(device);
  out.truncated = copy_buffer(truncated, {T, n}, torch::kUInt8).to(device);
  const auto last_value = critic.forward(agent_->input(current_observations(), current_conditions()));
  const auto following = torch::cat({out.values.slice(0, 1), last_value.unsqueeze(0)});
  out.next_values = torch::where(out.truncated > 0, copy_buffer(final_values, {T, n}, torch::kFloat32).to(device), following) * (1 - out.terminated);

  out.rewards = reward_source_->rewards(out);
  if (out.rewards.sizes() != out.env_rewards.sizes())
    throw std::runtime_error("RewardSource returned rewards of the wrong shape");
  agent_->normalizer().update_over_ranks(out.observations.reshape({-1, obs_dim_}));
  return out;
}

}  // namespace vaegail
