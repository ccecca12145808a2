// Shared by the rl tests: small deterministic environments and a training loop on one.
#pragma once

#include <gtest/gtest.h>
#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "env/env.h"
#include "env/vec_env.h"
#include "rl/agent.h"
#include "rl/rollout.h"
#include "rl/update_batch.h"
#include "util/rng.h"

namespace vaegail {

// Small networks train faster on one thread than on several here.
class SingleThreadTorch : public ::testing::Environment {
 public:
  void SetUp() override { torch::set_num_threads(1); }
};
inline ::testing::Environment* const kSingleThreadTorch =
    ::testing::AddGlobalTestEnvironment(new SingleThreadTorch);

// The Env boilerplate: specs, a one-value context, and a step counter with a time limit.
class ToyEnv : public Env {
 public:
  ToyEnv(std::string id, std::vector<std::string> obs_names, int episode_length)
      : id_(std::move(id)), episode_length_(episode_length) {
    obs_spec_.names = std::move(obs_names);
    obs_spec_.low.assign(obs_spec_.names.size(), -1e9);
    obs_spec_.high.assign(obs_spec_.names.size(), 1e9);
    act_spec_ = {{"force"}, {-1.0}, {1.0}};
  }
  const std::string& id() const override { return id_; }
  const BoxSpec& observation_spec() const override { return obs_spec_; }
  const BoxSpec& action_spec() const override { return act_spec_; }
  const std::vector<std::string>& feature_names() const override { return obs_spec_.names; }
  const std::vector<std::string>& context_names() const override { return context_names_; }
  double control_timestep() const override { return 0.1; }
  int episode_length() const override { return episode_length_; }
  void set_context(const std::vector<double>& context) override { context_ = context; }
  const std::vector<double>& context() const override { return context_; }
  void features(double* out) const override {
    std::vector<float> obs(obs_dim());
    observe(obs.data());
    std::copy(obs.begin(), obs.end(), out);
  }
  int steps_taken() const override { return steps_; }

  void reset(std::uint64_t seed) override {
    steps_ = 0;
    restart(seed);
  }
  StepOutcome step(const float* action) override {
    ++steps_;
    StepOutcome out = advance(action);
    out.truncated = !out.terminated && steps_ >= episode_length_;
    return out;
  }

 protected:
  virtual void restart(std::uint64_t seed) = 0;
  // The dynamics: sets reward and terminated.
  virtual StepOutcome advance(const float* action) = 0;

  std::vector<double> context_ = {0.0};
  int steps_ = 0;

 private:
  std::string id_;
  BoxSpec obs_spec_, act_spec_;
  std::vector<std::string> context_names_ = {"target"};
  int episode_length_;
};

// clone() for a ToyEnv that is default-constructible.
template <class Derived>
class ClonableToyEnv : public ToyEnv {
 public:
  using ToyEnv::ToyEnv;
  std::unique_ptr<Env> clone() const override {
    auto copy = std::make_unique<Derived>();
    copy->set_context(context_);
    return copy;
  }
};

// A 1-D point mass that must move to and stay at the target position given by its context.
// Observation (position, velocity); leaving [-2, 2] terminates the episode.
class PointMassEnv : public ClonableToyEnv<PointMassEnv> {
 public:
  PointMassEnv() : ClonableToyEnv("point_mass", {"x", "v"}, 50) {}
  void observe(float* out) const override {
    out[0] = static_cast<float>(x_);
    out[1] = static_cast<float>(v_);
  }

 protected:
  void restart(std::uint64_t seed) override {
    Rng rng(seed);
    x_ = rng.uniform(-1.0, 1.0);
    v_ = 0.0;
  }
  StepOutcome advance(const float* action) override {
    const double force = std::clamp(static_cast<double>(action[0]), -1.0, 1.0);
    v_ = 0.9 * v_ + 0.5 * force;
    x_ += 0.1 * v_;
    StepOutcome out;
    out.reward = 1.0 - std::abs(x_ - context_[0]);
    out.terminated = std::abs(x_) > 2.0;
    return out;
  }

 private:
  double x_ = 0.0, v_ = 0.0;
};

// Gives the rollout test known answers: observation (context, steps taken, seed-dependent
// value), reward 1 per step. With a positive context the episode terminates after 3 steps,
// otherwise the time limit of 5 truncates it.
class CountingEnv : public ClonableToyEnv<CountingEnv> {
 public:
  CountingEnv() : ClonableToyEnv("counting", {"context", "steps", "seed"}, 5) {}
  void observe(float* out) const override {
    out[0] = static_cast<float>(context_[0]);
    out[1] = static_cast<float>(steps_);
    out[2] = static_cast<float>(seed_value_);
  }

 protected:
  void restart(std::uint64_t seed) override { seed_value_ = static_cast<double>(seed % 1000) / 1000.0; }
  StepOutcome advance(const float*) override {
    StepOutcome out;
    out.reward = 1.0;
    out.terminated = context_[0] > 0 && steps_ >= 3;
    return out;
  }

 private:
  double seed_value_ = 0.0;
};

// Point-mass training: 8 environments, targets ±0.5 drawn per episode and given to the
// policy as its condition.
class PointMassTask {
 public:
  explicit PointMassTask(std::uint64_t seed)
      : agent_(seeded_agent(seed)),
        envs_(PointMassEnv(), 8),
        targets_(seed),
        collector_(envs_, agent_, seed, [this](int, Env& env) {
          const double target = targets_.uniform() < 0.5 ? -0.5 : 0.5;
          env.set_context({target});
          return std::vector<float>{static_cast<float>(target)};
        }) {}

  Agent& agent() { return *agent_; }

  // Mean episode return of each iteration's finished episodes.
  std::vector<double> train(int iterations, const std::function<void(const UpdateBatch&)>& update) {
    std::vector<double> returns;
    for (int it = 0; it < iterations; ++it) {
      const Rollout rollout = collector_.collect(100);
      double sum = 0;
      for (const auto& e : rollout.episodes) sum += e.env_return;
      returns.push_back(sum / std::max<size_t>(1, rollout.episodes.size()));
      update(make_update_batch(rollout));
    }
    return returns;
  }

 private:
  // The initial weights come from torch's global generator: seeded here, so that a run is fixed
  // by `seed` alone rather than by whatever the process drew before.
  static std::shared_ptr<Agent> seeded_agent(std::uint64_t seed) {
    torch::manual_seed(seed);
    return Agent::make_gaussian(options());
  }

  static AgentOptions options() {
    AgentOptions o;
    o.obs_dim = 2;
    o.condition_dim = 1;
    o.act_dim = 1;
    o.policy_hidden = o.critic_hidden = {32, 32};
    o.init_log_std = -0.5;
    return o;
  }

  std::shared_ptr<Agent> agent_;
  VecEnv envs_;
  Rng targets_;
  RolloutCollector collector_;
};

// Trains with Updater (Trpo or Ppo) for 40 iterations of 800 steps from a fixed seed: the
// random initial policy scores about 6, a policy that holds the target about 47 of 50.
template <class Updater, class Options>
void expect_solves_point_mass(const Options& options) {
  PointMassTask task(7);
  Updater updater(task.agent().policy_ptr(), task.agent().critic_ptr(), options);
  const auto returns = task.train(40, [&](const UpdateBatch& batch) { updater.update(batch); });
  std::cout << "point-mass mean return: first iteration " << returns.front() << ", last " << returns.back() << "\n";
  EXPECT_LT(returns.front(), 30.0);
  EXPECT_GT(returns.back(), 42.0);
}

}  // namespace vaegail
