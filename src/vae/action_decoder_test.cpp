#include "vae/action_decoder.h"

#include <gtest/gtest.h>

#include "vae/gaussian.h"

namespace vaegail::vae {
namespace {

TEST(ActionDecoderTest, GaussianPerStep) {
  torch::manual_seed(5);
  ActionDecoder dec(4, 3, 2, std::vector<int>{16, 8});
  const auto x = torch::randn({5, 7, 4}), z = torch::randn({5, 7, 3}), a = torch::randn({5, 7, 2});
  const auto d = dec->forward(x, z);
  EXPECT_EQ(d.mean.sizes(), torch::IntArrayRef({5, 7, 2}));
  EXPECT_EQ(d.log_std.sizes(), torch::IntArrayRef({5, 7, 2}));
  EXPECT_GE(d.log_std.min().item<double>(), ActionDecoderImpl::kMinLogStd);
  EXPECT_LE(d.log_std.max().item<double>(), ActionDecoderImpl::kMaxLogStd);
  EXPECT_TRUE(torch::equal(dec->mean(x, z), d.mean));
  const auto lp = dec->log_prob(x, z, a);
  EXPECT_EQ(lp.sizes(), torch::IntArrayRef({5, 7}));
  EXPECT_TRUE(torch::allclose(lp, gaussian_log_prob(a, d.mean, d.log_std).sum(-1)));
}

TEST(ActionDecoderTest, DependsOnStateAndLatent) {
  torch::manual_seed(6);
  ActionDecoder dec(4, 3, 2, std::vector<int>{16});
  const auto x = torch::randn({2, 4}), z = torch::randn({2, 3});
  const auto base = dec->mean(x, z);
  EXPECT_FALSE(torch::allclose(base, dec->mean(x, z + 1)));
  EXPECT_FALSE(torch::allclose(base, dec->mean(x + 1, z)));
}

TEST(ActionDecoderTest, ASharedStdIsTheSameAtEveryStepAndLearnsTheSpread) {
  torch::manual_seed(7);
  ActionDecoder dec(3, 2, 2, std::vector<int>{8}, /*state_dependent_std=*/false);
  const auto x = torch::randn({6, 3}), z = torch::randn({6, 2});
  const auto d = dec->forward(x, z);
  EXPECT_TRUE(torch::equal(d.log_std, d.log_std[0].expand({6, 2})));
  // The likelihood's gradient on the shared log-std is sum_i ((a_i - mu_i)^2 / sigma^2 - 1)
  // (the soft bound has slope 1 at the parameter's initial 0).
  const auto a = torch::randn({6, 2});
  dec->log_prob(x, z, a).sum().backward();
  const auto var = (2 * d.log_std.detach()).exp();
  const auto expected = ((a - d.mean.detach()).square() / var - 1).sum(0);
  EXPECT_TRUE(torch::allclose(dec->named_parameters()["shared_log_std"].grad(), expected, 1e-4, 1e-4));
}

}  // namespace
}  // namespace vaegail::vae
