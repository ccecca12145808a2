#include "rl/stochastic_policy.h"

#include <gtest/gtest.h>

#include <cmath>

#include "rl/gaussian_policy.h"
#include "rl/test_support.h"

namespace vaegail {
namespace {

DiagGaussian random_gaussian(int64_t batch, int64_t dim, uint64_t seed) {
  torch::manual_seed(seed);
  return {torch::randn({batch, dim}, torch::kFloat64), 0.5 * torch::randn({batch, dim}, torch::kFloat64)};
}

double at(const torch::Tensor& t, int64_t b, int64_t d) { return t[b][d].item<double>(); }

TEST(DiagGaussian, LogProbAndEntropyMatchTheUnivariateFormulas) {
  const auto g = random_gaussian(4, 3, 1);
  const auto actions = torch::randn({4, 3}, torch::kFloat64);
  const auto log_prob = g.log_prob(actions), entropy = g.entropy();
  ASSERT_EQ(log_prob.sizes(), torch::IntArrayRef({4}));
  ASSERT_EQ(entropy.sizes(), torch::IntArrayRef({4}));
  for (int64_t b = 0; b < 4; ++b) {
    double lp = 0, h = 0;
    for (int64_t d = 0; d < 3; ++d) {
      const double mu = at(g.mean, b, d), sigma = std::exp(at(g.log_std, b, d)), a = at(actions, b, d);
      lp += std::log(std::exp(-0.5 * std::pow((a - mu) / sigma, 2)) / (sigma * std::sqrt(2 * M_PI)));
      h += 0.5 * std::log(2 * M_PI * M_E * sigma * sigma);
    }
    EXPECT_NEAR(log_prob[b].item<double>(), lp, 1e-10);
    EXPECT_NEAR(entropy[b].item<double>(), h, 1e-10);
  }
}

TEST(DiagGaussian, KlMatchesTheClosedFormAndMonteCarlo) {
  const auto p = random_gaussian(3, 2, 2), q = random_gaussian(3, 2, 3);
  const auto kl = kl_divergence(p, q);
  ASSERT_EQ(kl.sizes(), torch::IntArrayRef({3}));
  for (int64_t b = 0; b < 3; ++b) {
    double expected = 0;
    for (int64_t d = 0; d < 2; ++d) {
      const double sp = std::exp(at(p.log_std, b, d)), sq = std::exp(at(q.log_std, b, d));
      const double dm = at(p.mean, b, d) - at(q.mean, b, d);
      expected += std::log(sq / sp) + (sp * sp + dm * dm) / (2 * sq * sq) - 0.5;
    }
    EXPECT_NEAR(kl[b].item<double>(), expected, 1e-10);
  }
  // E_p[log p − log q] by sampling, for an independent check of the formula itself.
  const int64_t n = 400000;
  const DiagGaussian p0{p.mean.slice(0, 0, 1).expand({n, 2}), p.log_std.slice(0, 0, 1).expand({n, 2})};
  const DiagGaussian q0{q.mean.slice(0, 0, 1).expand({n, 2}), q.log_std.slice(0, 0, 1).expand({n, 2})};
  auto gen = at::detail::createCPUGenerator(5);
  const auto x = p0.sample(gen);
  EXPECT_NEAR((p0.log_prob(x) - q0.log_prob(x)).mean().item<double>(), kl[0].item<double>(), 0.02);
  EXPECT_NEAR(kl_divergence(p, p).abs().max().item<double>(), 0.0, 1e-12);
}

TEST(DiagGaussian, SamplesHaveTheDistributionsMomentsAndFollowTheGenerator) {
  const DiagGaussian g{torch::tensor({{1.0, -2.0}}).expand({100000, 2}),
                       torch::tensor({{std::log(0.5), std::log(2.0)}}).expand({100000, 2})};
  auto gen = at::detail::createCPUGenerator(11), same = at::detail::createCPUGenerator(11);
  const auto x = g.sample(gen);
  EXPECT_NEAR(x.mean(0)[0].item<double>(), 1.0, 0.01);
  EXPECT_NEAR(x.mean(0)[1].item<double>(), -2.0, 0.04);
  EXPECT_NEAR(x.std(0)[0].item<double>(), 0.5, 0.01);
  EXPECT_NEAR(x.std(0)[1].item<double>(), 2.0, 0.04);
  EXPECT_TRUE(torch::equal(x, g.sample(same)));
}

TEST(GaussianPolicy, ShapesInitialSigmaAndTheConditionReachesTheMean) {
  GaussianPolicyOptions o;
  o.input_dim = 5;  // 3 observation + 2 condition
  o.act_dim = 2;
  o.hidden = {8, 8};
  o.init_log_std = -2.0;
  o.output_gain = 1.0;
  GaussianPolicy policy(o);
  torch::manual_seed(0);
  auto input = torch::randn({7, 5});
  const auto d = policy.distribution(input);
  EXPECT_EQ(d.mean.sizes(), torch::IntArrayRef({7, 2}));
  EXPECT_EQ(d.log_std.sizes(), torch::IntArrayRef({7, 2}));
  EXPECT_TRUE(torch::allclose(d.log_std, torch::full({7, 2}, -2.0)));
  auto other_condition = input.clone();
  other_condition.slice(1, 3) += 1.0;
  EXPECT_FALSE(torch::allclose(policy.distribution(other_condition).mean, d.mean));
  EXPECT_EQ(policy.trainable_parameters().size(), policy.parameters().size());
}

TEST(Mlp, OutputGainScalesTheInitialOutputs) {
  torch::manual_seed(0);
  Mlp wide(4, {64, 64}, 3, Activation::Relu, 1.0), small(4, {64, 64}, 3, Activation::Relu, 0.01);
  const auto x = torch::randn({256, 4});
  const double ratio = small.forward(x).std().item<double>() / wide.forward(x).std().item<double>();
  EXPECT_LT(ratio, 0.05);
  EXPECT_EQ(wide.forward(x).sizes(), torch::IntArrayRef({256, 3}));
}

}  // namespace
}  // namespace vaegail
