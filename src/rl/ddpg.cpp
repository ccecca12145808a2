#include "rl/ddpg.h"

#include <ATen/CPUGeneratorImpl.h>

#include <stdexcept>

#include "util/checkpoint_file.h"
#include "util/rng.h"

namespace vaegail {

ReplayBuffer::ReplayBuffer(int obs_dim, int act_dim, int64_t capacity)
    : obs_dim_(obs_dim), act_dim_(act_dim), capacity_(capacity) {
  if (capacity < 1) throw std::invalid_argument("ReplayBuffer: capacity must be positive");
  obs_ = torch::zeros({capacity, obs_dim});
  actions_ = torch::zeros({capacity, act_dim});
  rewards_ = torch::zeros({capacity});
  next_obs_ = torch::zeros({capacity, obs_dim});
  terminated_ = torch::zeros({capacity});
}

void ReplayBuffer::add(const float* obs, const float* action, double reward, const float* next_obs,
                       bool terminated) {
  std::copy(obs, obs + obs_dim_, obs_.data_ptr<float>() + next_ * obs_dim_);
  std::copy(action, action + act_dim_, actions_.data_ptr<float>() + next_ * act_dim_);
  std::copy(next_obs, next_obs + obs_dim_, next_obs_.data_ptr<float>() + next_ * obs_dim_);
  rewards_.data_ptr<float>()[next_] = static_cast<float>(reward);
  terminated_.data_ptr<float>()[next_] = terminated ? 1.0f : 0.0f;
  next_ = (next_ + 1) % capacity_;
  size_ = std::min(size_ + 1, capacity_);
}

ReplayBuffer::Batch ReplayBuffer::sample(int batch, torch::Generator& generator) const {
  if (size_ == 0) throw std::logic_error("ReplayBuffer: sample from an empty buffer");
  const auto index = torch::randint(size_, {batch}, generator, torch::kLong);
  return {obs_.index_select(0, index), actions_.index_select(0, index), rewards_.index_select(0, index),
          next_obs_.index_select(0, index), terminated_.index_select(0, index)};
}

torch::Tensor td_target(const torch::Tensor& rewards, const torch::Tensor& terminated, const torch::Tensor& q_next,
                        double gamma) {
  return rewards + gamma * (1.0 - terminated) * q_next;
}

void soft_update(torch::nn::Module& target, const torch::nn::Module& source, double tau) {
  torch::NoGradGuard no_grad;
  const auto from = source.parameters();
  auto to = target.parameters();
  if (from.size() != to.size()) throw std::invalid_argument("soft_update: the networks differ in shape");
  for (size_t i = 0; i < to.size(); ++i) to[i].mul_(1.0 - tau).add_(from[i], tau);
}

Ddpg::Ddpg(int obs_dim, const BoxSpec& action_spec, DdpgOptions options)
    : options_(std::move(options)),
      buffer_(obs_dim, action_spec.dim(), options_.buffer_capacity),
      generator_(at::detail::createCPUGenerator(options_.seed)) {
  const int act_dim = action_spec.dim();
  low_ = torch::tensor(std::vector<double>(action_spec.low), torch::kFloat32);
  high_ = torch::tensor(std::vector<double>(action_spec.high), torch::kFloat32);
  torch::manual_seed(options_.seed);
  // A small output gain starts the actor in the middle of the action box, far from tanh's
  // flat tails where its gradient vanishes.
  const auto make_actor = [&] {
    return std::make_shared<Mlp>(obs_dim, options_.actor_hidden, act_dim, Activation::Relu, 0.1);
  };
  const auto make_critic = [&] {
    return std::make_shared<Mlp>(obs_dim + act_dim, options_.critic_hidden, 1, Activation::Relu);
  };
  actor_ = make_actor();
  target_actor_ = make_actor();
  critic_ = make_critic();
  target_critic_ = make_critic();
  soft_update(*target_actor_, *actor_, 1.0);
  soft_update(*target_critic_, *critic_, 1.0);
  actor_optimizer_ = std::make_unique<torch::optim::Adam>(actor_->parameters(),
                                                          torch::optim::AdamOptions(options_.actor_learning_rate));
  critic_optimizer_ = std::make_unique<torch::optim::Adam>(critic_->parameters(),
                                                           torch::optim::AdamOptions(options_.critic_learning_rate));
}

torch::Tensor Ddpg::squash(const torch::Tensor& pre_activation) const {
  return low_ + (torch::tanh(pre_activation) + 1.0) * 0.5 * (high_ - low_);
}

torch::Tensor Ddpg::act(const torch::Tensor& obs) { return squash(actor_->forward(obs)); }

torch::Tensor Ddpg::q(const torch::Tensor& obs, const torch::Tensor& actions) {
  return critic_->forward(torch::cat({obs, actions}, 1)).squeeze(1);
}

torch::Tensor Ddpg::critic_targets(const ReplayBuffer::Batch& b) {
  torch::NoGradGuard no_grad;
  const auto next_action = squash(target_actor_->forward(b.next_obs));
  const auto q_next = target_critic_->forward(torch::cat({b.next_obs, next_action}, 1)).squeeze(1);
  return td_target(b.rewards, b.terminated, q_next, options_.gamma);
}

DdpgStats Ddpg::update(const ReplayBuffer::Batch& b) {
  DdpgStats stats;
  const auto y = critic_targets(b);
  const auto critic_loss = (q(b.obs, b.actions) - y).pow(2).mean();
  critic_optimizer_->zero_grad();
  critic_loss.backward();
  critic_optimizer_->step();
  stats.critic_loss = critic_loss.item<double>();

  const auto pre_activation = actor_->forward(b.obs);
  const auto objective = q(b.obs, squash(pre_activation)).mean();
  actor_optimizer_->zero_grad();
  (options_.pre_activation_penalty * pre_activation.pow(2).mean() - objective).backward();  // the critic's gradients from this pass are cleared before its next step
  actor_optimizer_->step();
  stats.actor_objective = objective.item<double>();

  soft_update(*target_actor_, *actor_, options_.tau);
  soft_update(*target_critic_, *critic_, options_.tau);
  return stats;
}

std::vector<float> Ddpg::explore(const std::vector<float>& obs, int64_t step) {
  const int act_dim = static_cast<int>(low_.size(0));
  torch::Tensor action;
  if (step < options_.warmup_steps) {
    action = low_ + torch::rand({act_dim}, generator_) * (high_ - low_);
  } else {
    torch::NoGradGuard no_grad;
    const auto mean = act(torch::tensor(obs).unsqueeze(0)).squeeze(0);
    action = torch::max(torch::min(mean + options_.exploration_std * torch::randn({act_dim}, generator_), high_), low_);
  }
  return std::vector<float>(action.data_ptr<float>(), action.data_ptr<float>() + act_dim);
}

DdpgStats Ddpg::train(Env& env, int64_t steps) {
  DdpgStats stats;
  env.reset(derive_seed(options_.seed, episode_seed_++));
  auto obs = env.observation();
  for (int64_t t = 0; t < steps; ++t, ++steps_trained_) {
    const auto action = explore(obs, steps_trained_);
    const StepOutcome out = env.step(action.data());
    const auto next = env.observation();
    buffer_.add(obs.data(), action.data(), out.reward, next.data(), out.terminated);
    obs = next;
    if (out.done()) {
      env.reset(derive_seed(options_.seed, episode_seed_++));
      obs = env.observation();
    }
    if (buffer_.size() >= options_.batch_size) stats = update(buffer_.sample(options_.batch_size, generator_));
  }
  return stats;
}

void Ddpg::save_actor(const std::string& path) {
  torch::serialize::OutputArchive archive;
  actor_->save(archive);
  write_checkpoint(path, [&](std::ostream& out) { archive.save_to(out); });
}

void Ddpg::load_actor(const std::string& path) {
  // Module::load takes tensors of any shape, so the file is read into a scratch copy first.
  Mlp loaded(actor_->in_dim(), options_.actor_hidden, actor_->out_dim(), Activation::Relu);
  try {
    torch::serialize::InputArchive archive;
    archive.load_from(path);
    loaded.load(archive);
  } catch (const c10::Error& e) {
    throw std::runtime_error(path + ": not a DDPG actor (" + e.what_without_backtrace() + ")");
  }
  const auto want = actor_->parameters(), have = loaded.parameters();
  for (size_t i = 0; i < want.size(); ++i)
    if (i >= have.size() || want[i].sizes() != have[i].sizes())
      throw std::runtime_error(path + ": the actor's layer sizes differ from this DDPG's");
  soft_update(*actor_, loaded, 1.0);
  soft_update(*target_actor_, *actor_, 1.0);
}

double Ddpg::evaluate(const Env& prototype, int episodes, std::uint64_t base_seed) {
  torch::NoGradGuard no_grad;
  auto env = prototype.clone();
  double total = 0;
  for (int e = 0; e < episodes; ++e) {
    env->reset(base_seed + e);
    for (bool done = false; !done;) {
      const auto obs = env->observation();
      const auto action = act(torch::tensor(obs).unsqueeze(0)).squeeze(0).contiguous();
      const StepOutcome out = env->step(action.data_ptr<float>());
      total += out.reward;
      done = out.done();
    }
  }
  return total / episodes;
}

}  // namespace vaegail
