#include "rl/rollout.h"

#include <gtest/gtest.h>

#include <map>

#include "rl/test_support.h"
#include "rl/update_batch.h"

namespace vaegail {
namespace {

std::shared_ptr<Agent> counting_agent(int condition_dim) {
  AgentOptions o;
  o.obs_dim = 3;
  o.condition_dim = condition_dim;
  o.act_dim = 1;
  o.policy_hidden = o.critic_hidden = {8};
  return Agent::make_gaussian(o);
}

// Per environment, episodes alternate between a positive context (terminates after 3 steps)
// and a negative one (truncated after 5); the condition is (context, episode number).
struct AlternatingContext {
  std::map<int, int> episodes_started;
  std::vector<float> operator()(int env_index, Env& env) {
    const int k = episodes_started[env_index]++;
    const double context = k % 2 == 0 ? 1.0 : -1.0;
    env.set_context({context});
    return {static_cast<float>(context), static_cast<float>(k)};
  }
};

class ScaledReward : public RewardSource {
 public:
  torch::Tensor rewards(const Rollout& r) override { return r.env_rewards * 3 + r.actions.squeeze(-1); }
};

TEST(RolloutCollector, StoresStepsConditionsAndBootstrapValuesAcrossCollections) {
  auto agent = counting_agent(2);
  VecEnv envs(CountingEnv(), 2);
  agent->normalizer().set_frozen(true);  // keeps the inputs reproducible after collection
  AlternatingContext hook;
  RolloutCollector collector(envs, agent, 42, std::ref(hook), std::make_shared<ScaledReward>());
  const Rollout first = collector.collect(4);
  const Rollout r = collector.collect(6);  // steps 4..9: an episode spans both collections

  ASSERT_EQ(r.observations.sizes(), torch::IntArrayRef({6, 2, 3}));
  ASSERT_EQ(r.conditions.sizes(), torch::IntArrayRef({6, 2, 2}));
  ASSERT_EQ(r.inputs.sizes(), torch::IntArrayRef({6, 2, 5}));
  ASSERT_EQ(r.actions.sizes(), torch::IntArrayRef({6, 2, 1}));
  for (const auto& t : {r.log_probs, r.values, r.next_values, r.env_rewards, r.rewards, r.terminated, r.truncated})
    ASSERT_EQ(t.sizes(), torch::IntArrayRef({6, 2}));

  // The episode pattern is 3 terminated steps, then 5 truncated: steps 0-2, 3-7, 8-10, ...
  const auto obs = torch::cat({first.observations, r.observations});
  const auto cond = torch::cat({first.conditions, r.conditions});
  const std::vector<int> steps_in_episode = {0, 1, 2, 0, 1, 2, 3, 4, 0, 1};
  const std::vector<int> episode_of_step = {0, 0, 0, 1, 1, 1, 1, 1, 2, 2};
  for (int t = 0; t < 10; ++t) {
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(obs[t][i][1].item<float>(), steps_in_episode[t]) << "t=" << t;
      EXPECT_EQ(cond[t][i][1].item<float>(), episode_of_step[t]) << "t=" << t;
      // The hook set the context before the episode's first observation.
      EXPECT_EQ(obs[t][i][0].item<float>(), cond[t][i][0].item<float>()) << "t=" << t;
    }
  }
  EXPECT_TRUE(torch::equal(r.terminated.select(1, 0), torch::tensor({0.f, 0.f, 0.f, 0.f, 0.f, 0.f})));
  EXPECT_TRUE(torch::equal(r.truncated.select(1, 0), torch::tensor({0.f, 0.f, 0.f, 1.f, 0.f, 0.f})));
  EXPECT_TRUE(torch::equal(first.terminated.select(1, 1), torch::tensor({0.f, 0.f, 1.f, 0.f})));

  // next_values: the following step's value inside an episode, 0 after termination, V of the
  // final observation (still with the finished episode's condition) after truncation.
  torch::NoGradGuard no_grad;
  EXPECT_TRUE(torch::allclose(r.next_values.slice(0, 0, 3), r.values.slice(0, 1, 4)));
  EXPECT_TRUE(torch::allclose(r.next_values.slice(0, 4, 5), r.values.slice(0, 5, 6)));
  EXPECT_TRUE(torch::equal(first.next_values[2], torch::zeros({2})));
  const auto final_obs = torch::tensor({{-1.f, 5.f, obs[7][0][2].item<float>()}});
  const auto expected = agent->critic().forward(agent->input(final_obs, torch::tensor({{-1.f, 1.f}})));
  EXPECT_NEAR(r.next_values[3][0].item<float>(), expected[0].item<float>(), 1e-6);
  EXPECT_TRUE(torch::allclose(r.log_probs, agent->policy().distribution(r.inputs.reshape({12, 5}))
                                               .log_prob(r.actions.reshape({12, 1}))
                                               .reshape({6, 2})));

  EXPECT_TRUE(torch::allclose(r.rewards, r.env_rewards * 3 + r.actions.squeeze(-1)));
  ASSERT_EQ(first.episodes.size(), 2u);
  EXPECT_TRUE(first.episodes[0].terminated);
  EXPECT_EQ(first.episodes[0].length, 3);
  ASSERT_EQ(r.episodes.size(), 2u);
  EXPECT_EQ(r.episodes[0].env_index, 0);
  EXPECT_FALSE(r.episodes[0].terminated);
  EXPECT_EQ(r.episodes[0].length, 5);
  EXPECT_DOUBLE_EQ(r.episodes[0].env_return, 5.0);
  EXPECT_EQ(r.episodes[0].condition, (std::vector<float>{-1.f, 1.f}));
  EXPECT_DOUBLE_EQ(agent->normalizer().count(), 0.0);
}

TEST(RolloutCollector, TheSameSeedGivesTheSameRollout) {
  const auto run = [](std::uint64_t seed) {
    torch::manual_seed(0);
    auto agent = counting_agent(0);
    VecEnv envs(CountingEnv(), 3);
    RolloutCollector collector(envs, agent, seed);
    collector.collect(7);
    return collector.collect(7);
  };
  const Rollout a = run(5), b = run(5), c = run(6);
  EXPECT_TRUE(torch::equal(a.actions, b.actions));
  EXPECT_TRUE(torch::equal(a.observations, b.observations));
  EXPECT_FALSE(torch::equal(a.actions, c.actions));
  EXPECT_FALSE(torch::equal(a.observations, c.observations));  // the seeds reach the environments
}

TEST(RolloutCollector, RejectsAConditionedAgentWithoutAHook) {
  VecEnv envs(CountingEnv(), 1);
  EXPECT_THROW(RolloutCollector(envs, counting_agent(2), 0), std::invalid_argument);
}

TEST(UpdateBatch, FlattensTheRolloutAndPartitionsIt) {
  auto agent = counting_agent(0);
  VecEnv envs(CountingEnv(), 2);
  RolloutCollector collector(envs, agent, 1);
  const UpdateBatch batch = make_update_batch(collector.collect(8));
  ASSERT_EQ(batch.size(), 16);
  EXPECT_DOUBLE_EQ(agent->normalizer().count(), 16.0);  // the collection's observations
  EXPECT_EQ(batch.inputs.sizes(), torch::IntArrayRef({16, 3}));
  EXPECT_EQ(batch.actions.sizes(), torch::IntArrayRef({16, 1}));
  EXPECT_NEAR(batch.advantages.mean().item<double>(), 0.0, 1e-5);
  EXPECT_NEAR(batch.advantages.std().item<double>(), 1.0, 1e-4);
  auto gen = at::detail::createCPUGenerator(0);
  const auto parts = batch.minibatches(3, gen);
  ASSERT_EQ(parts.size(), 3u);
  int64_t total = 0;
  for (const auto& p : parts) total += p.size();
  EXPECT_EQ(total, 16);
  EXPECT_NEAR(torch::cat({parts[0].returns, parts[1].returns, parts[2].returns}).sum().item<double>(),
              batch.returns.sum().item<double>(), 1e-4);
}

}  // namespace
}  // namespace vaegail
