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

}  // namespace

RolloutCollector::RolloutCollector(VecEnv& envs, std::shared_ptr<Agent> agent, std::uint64_t seed,
                                   EpisodeStartFn on_episode_start, std::shared_ptr<RewardSource> reward_source)
    : envs_(envs),
      agent_(std::move(agent)),
      on_episode_start_(std::move(on_episode_start)),
      reward_source_(std::move(reward_source)),
      // Environment i uses stream i of the seed; the action noise the stream after them.
      generator_(at::detail::createCPUGenerator(derive_seed(seed, envs.size()))),
      obs_dim_(envs.obs_dim()),
      cond_dim_(agent_->condition_dim()) {
  if (envs.obs_dim() != agent_->obs_dim() || envs.act_dim() != agent_->act_dim())
    throw std::invalid_argument("RolloutCollector: environment (obs " + std::to_string(envs.obs_dim()) + ", act " +
                                std::to_string(envs.act_dim()) + ") does not fit the agent (obs " +
                                std::to_string(agent_->obs_dim()) + ", act " + std::to_string(agent_->act_dim()) +
                                ")");
  if (cond_dim_ > 0 && !on_episode_start_)
    throw std::invalid_argument("RolloutCollector: the agent takes a condition but no episode-start hook gives one");
  for (int i = 0; i < envs.size(); ++i) seeds_.push_back(derive_seed(seed, i));
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
  const int n = envs_.size();
  const auto device = agent_->device();
  StochasticPolicy& policy = agent_->policy();
  Critic& critic = agent_->critic();

  std::vector<torch::Tensor> observations, conditions, inputs, actions, log_probs, values, rewards, terminated,
      truncated, final_values;
  Rollout out;
  for (int t = 0; t < steps_per_env; ++t) {
    const auto obs = current_observations(), cond = current_conditions();
    const auto input = agent_->input(obs, cond);
    const auto dist = policy.distribution(input);
    const auto action = dist.sample(generator_);
    const auto action_cpu = action.to(torch::kCPU).contiguous();
    envs_.step(action_cpu.data_ptr<float>());

    observations.push_back(obs.to(device));
    conditions.push_back(cond.to(device));
    inputs.push_back(input);
    actions.push_back(action);
    log_probs.push_back(dist.log_prob(action));
    values.push_back(critic.forward(input));
    rewards.push_back(copy_buffer(envs_.rewards(), {n}, torch::kFloat32));
    terminated.push_back(copy_buffer(envs_.terminated(), {n}, torch::kUInt8));
    truncated.push_back(copy_buffer(envs_.truncated(), {n}, torch::kUInt8));
    auto final_value = torch::zeros({n}, device);
    if (truncated.back().any().item<bool>()) {
      // The finished episode's condition is still in `cond`: begin_episode below replaces it.
      const auto final_obs = copy_buffer(envs_.final_observations(), {n, obs_dim_}, torch::kFloat32);
      final_value = critic.forward(agent_->input(final_obs, cond));
    }
    final_values.push_back(final_value);

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

  out.observations = torch::stack(observations);
  out.conditions = torch::stack(conditions);
  out.inputs = torch::stack(inputs);
  out.actions = torch::stack(actions);
  out.log_probs = torch::stack(log_probs);
  out.values = torch::stack(values);
  out.env_rewards = torch::stack(rewards).to(device);
  out.terminated = torch::stack(terminated).to(device);
  out.truncated = torch::stack(truncated).to(device);
  const auto last_value = critic.forward(agent_->input(current_observations(), current_conditions()));
  const auto following = torch::cat({out.values.slice(0, 1), last_value.unsqueeze(0)});
  out.next_values = torch::where(out.truncated > 0, torch::stack(final_values), following) * (1 - out.terminated);

  out.rewards = reward_source_->rewards(out);
  if (out.rewards.sizes() != out.env_rewards.sizes())
    throw std::runtime_error("RewardSource returned rewards of the wrong shape");
  agent_->normalizer().update(out.observations.reshape({-1, obs_dim_}));
  return out;
}

}  // namespace vaegail
