#include "rl/ddpg.h"

#include <gtest/gtest.h>

#include <ATen/CPUGeneratorImpl.h>

#include "rl/test_support.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

TEST(Ddpg, TdTargetMatchesHandComputedValues) {
  const auto r = torch::tensor({1.0f, 0.5f, -2.0f});
  const auto terminated = torch::tensor({0.0f, 1.0f, 0.0f});
  const auto q_next = torch::tensor({10.0f, 10.0f, 4.0f});
  const auto y = td_target(r, terminated, q_next, 0.9);
  EXPECT_NEAR(y[0].item<float>(), 1.0 + 0.9 * 10.0, 1e-5);  // bootstraps
  EXPECT_NEAR(y[1].item<float>(), 0.5, 1e-6);               // terminated: no bootstrap
  EXPECT_NEAR(y[2].item<float>(), -2.0 + 0.9 * 4.0, 1e-5);
}

TEST(Ddpg, SoftUpdateMovesTargetsByTau) {
  torch::manual_seed(0);
  Mlp source(3, {4}, 2), target(3, {4}, 2);
  std::vector<torch::Tensor> before;
  for (const auto& p : target.parameters()) before.push_back(p.detach().clone());
  soft_update(target, source, 0.25);
  const auto s = source.parameters();
  const auto t = target.parameters();
  for (size_t i = 0; i < t.size(); ++i) EXPECT_TRUE(torch::allclose(t[i], 0.25 * s[i] + 0.75 * before[i]));
  soft_update(target, source, 1.0);
  for (size_t i = 0; i < t.size(); ++i) EXPECT_TRUE(torch::equal(t[i], s[i]));
}

TEST(Ddpg, CriticTargetsComeFromTheTargetNetworks) {
  PointMassEnv env;
  Ddpg ddpg(env.obs_dim(), env.action_spec());
  auto generator = at::detail::createCPUGenerator(1);
  const float obs[2] = {0.1f, 0.2f}, next[2] = {0.3f, -0.1f}, action[1] = {0.5f};
  ddpg.buffer().add(obs, action, 0.7, next, false);
  const auto batch = ddpg.buffer().sample(4, generator);
  // By hand: y = r + γ Q'(s', μ'(s')).
  torch::NoGradGuard no_grad;
  const auto next_action = torch::tanh(ddpg.target_actor().forward(batch.next_obs));  // the box is [-1, 1]
  const auto q_next = ddpg.target_critic().forward(torch::cat({batch.next_obs, next_action}, 1)).squeeze(1);
  EXPECT_TRUE(torch::allclose(ddpg.critic_targets(batch), 0.7 + 0.99 * q_next, 1e-5, 1e-6));
  // Moving the online networks does not move the targets.
  for (auto& p : ddpg.actor().parameters()) p.add_(1.0);
  for (auto& p : ddpg.critic().parameters()) p.add_(1.0);
  EXPECT_TRUE(torch::allclose(ddpg.critic_targets(batch), 0.7 + 0.99 * q_next, 1e-5, 1e-6));
}

TEST(Ddpg, ReplayBufferOverwritesItsOldestTransitions) {
  ReplayBuffer buffer(1, 1, 3);
  for (int i = 0; i < 5; ++i) {
    const float x = static_cast<float>(i);
    buffer.add(&x, &x, i, &x, i == 4);
  }
  EXPECT_EQ(buffer.size(), 3);
  auto generator = at::detail::createCPUGenerator(2);
  const auto b = buffer.sample(200, generator);
  EXPECT_GE(b.rewards.min().item<float>(), 2.0f);  // 0 and 1 were overwritten
  EXPECT_EQ(b.rewards.max().item<float>(), 4.0f);
  EXPECT_TRUE(torch::equal(b.obs.squeeze(1), b.rewards));
  EXPECT_TRUE(torch::equal(b.terminated, (b.rewards == 4.0f).to(torch::kFloat32)));
}

// The point mass with its target fixed at 0.5: the untrained actor scores about 2 of 50 from
// starts in [-1, 1]; a policy that goes there and stays scores above 40.
TEST(Ddpg, ASavedActorActsTheSameWhenLoadedAndAStrangeFileIsRefused) {
  const BoxSpec box{{"a", "b"}, {-1.0, 0.0}, {1.0, 2.0}};
  DdpgOptions options;
  options.seed = 3;
  Ddpg trained(4, box, options);
  options.seed = 4;
  Ddpg fresh(4, box, options);
  const auto obs = torch::randn({5, 4});
  ASSERT_FALSE(torch::allclose(trained.act(obs), fresh.act(obs)));
  const std::string path = ::testing::TempDir() + "/ddpg_actor.pt";
  trained.save_actor(path);
  fresh.load_actor(path);
  EXPECT_TRUE(torch::equal(trained.act(obs), fresh.act(obs)));
  EXPECT_TRUE(torch::equal(trained.act(obs), fresh.target_actor().forward(obs).tanh().add(1).mul(0.5) *
                                                 torch::tensor({2.0f, 2.0f}) + torch::tensor({-1.0f, 0.0f})));
  options.actor_hidden = {8};
  Ddpg other_shape(4, box, options);
  EXPECT_THROW(other_shape.load_actor(path), std::runtime_error);
}

// The arm expert's actor on a full file system: refused in one line, the one before kept.
TEST(Ddpg, AnActorSavedOnAFullDiskIsRefusedAndTheOneBeforeStillLoads) {
  SmallFileSystem small(512 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const BoxSpec box{{"a", "b"}, {-1.0, 0.0}, {1.0, 2.0}};
  Ddpg ddpg(4, box, DdpgOptions{});
  const std::string path = small.path("actor.pt");
  expect_refused_on_a_full_disk_then_saved(small, path, [&] { ddpg.save_actor(path); });
  ddpg.load_actor(path);
}

TEST(Ddpg, SolvesThePointMassTaskWithinAFixedBudget) {
  PointMassEnv env;
  env.set_context({0.5});
  DdpgOptions options;
  options.seed = 3;
  Ddpg ddpg(env.obs_dim(), env.action_spec(), options);
  const double before = ddpg.evaluate(env, 10, 1000);
  ddpg.train(env, 4000);
  const double after = ddpg.evaluate(env, 10, 1000);
  std::cout << "DDPG point mass: return " << before << " -> " << after << " of 50\n";
  EXPECT_GT(after, 40.0);
}

}  // namespace
}  // namespace vaegail
