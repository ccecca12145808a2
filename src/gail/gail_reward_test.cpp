#include "gail/gail_reward.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gail/test_support.h"

namespace vaegail {
namespace {

TEST(GailReward, IsMinusLogOneMinusDAndRespectsTheClip) {
  const auto logits = torch::linspace(-8, 8, 33, torch::kFloat64);
  const auto rewards = gail_reward(logits, 3.0);
  for (int i = 0; i < logits.size(0); ++i) {
    const double l = logits[i].item<double>();
    const double d = 1.0 / (1.0 + std::exp(-l));
    EXPECT_NEAR(rewards[i].item<double>(), std::min(-std::log(1.0 - d), 3.0), 1e-9) << "logit " << l;
  }
  EXPECT_NEAR(gail_reward(torch::zeros({1}))[0].item<double>(), std::log(2.0), 1e-6);  // D = 1/2
}

TEST(GailReward, StaysFiniteWhereOneMinusDRoundsToZero) {
  const auto r = gail_reward(torch::tensor({40.f, 1e4f}), 1e9);
  EXPECT_NEAR(r[0].item<double>(), 40.0, 1e-4);  // softplus(l) → l, while 1 - sigmoid(40.f) == 0
  EXPECT_TRUE(std::isfinite(r[1].item<double>()));
  EXPECT_DOUBLE_EQ(gail_reward(torch::tensor({1e4f}))[0].item<double>(), kDefaultGailRewardClip);
}

TEST(GailReward, ScoresEveryStepOfARolloutWithItsCondition) {
  torch::manual_seed(1);
  DiscriminatorOptions o;
  o.obs_dim = 3;
  o.act_dim = 2;
  o.latent_dim = 2;
  o.hidden = {8};
  auto d = std::make_shared<Discriminator>(o);
  const int T = 4, N = 3;
  Rollout r;
  r.observations = torch::randn({T, N, 3});
  r.actions = torch::randn({T, N, 2});
  r.conditions = torch::randn({T, N, 2});
  r.env_rewards = torch::zeros({T, N});
  GailReward source(d, 1.5);
  const auto rewards = source.rewards(r);
  ASSERT_EQ(rewards.sizes(), torch::IntArrayRef({T, N}));
  torch::NoGradGuard no_grad;
  for (int t = 0; t < T; ++t)
    for (int n = 0; n < N; ++n) {
      const auto l = d->forward(r.observations[t][n].unsqueeze(0), r.actions[t][n].unsqueeze(0),
                                r.conditions[t][n].unsqueeze(0));
      EXPECT_NEAR(rewards[t][n].item<double>(), std::min(std::log1p(std::exp(l.item<double>())), 1.5), 1e-5);
    }
  Rollout other = r;
  other.conditions = -r.conditions;
  EXPECT_FALSE(torch::allclose(source.rewards(other), rewards));
}

}  // namespace
}  // namespace vaegail
