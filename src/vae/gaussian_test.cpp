#include "vae/gaussian.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vaegail::vae {
namespace {

TEST(GaussianTest, KlMatchesClosedFormPerDimension) {
  torch::manual_seed(1);
  const auto mean = torch::randn({4, 6}, torch::kDouble);
  const auto log_std = 0.7 * torch::randn({4, 6}, torch::kDouble);
  const auto kl = kl_to_standard_normal(mean, log_std);
  ASSERT_EQ(kl.sizes(), torch::IntArrayRef({4}));
  for (int b = 0; b < 4; ++b) {
    double expected = 0;
    for (int j = 0; j < 6; ++j) {
      const double m = mean[b][j].item<double>(), s = std::exp(log_std[b][j].item<double>());
      // KL(N(m, s^2) || N(0, 1)) = log(1 / s) + (s^2 + m^2) / 2 - 1/2
      expected += std::log(1.0 / s) + (s * s + m * m) / 2.0 - 0.5;
    }
    EXPECT_NEAR(kl[b].item<double>(), expected, 1e-12);
  }
  EXPECT_EQ(kl_to_standard_normal(torch::zeros({3}), torch::zeros({3})).item<double>(), 0.0);
}

TEST(GaussianTest, KlMatchesMonteCarlo) {
  torch::manual_seed(2);
  const auto mean = torch::tensor({0.5, -1.0}, torch::kDouble);
  const auto log_std = torch::tensor({-0.3, 0.4}, torch::kDouble);
  const auto z = reparameterize(mean, log_std, torch::randn({200000, 2}, torch::kDouble));
  const auto log_q = gaussian_log_prob(z, mean, log_std).sum(-1);
  const auto log_p = gaussian_log_prob(z, torch::zeros(2, torch::kDouble),
                                       torch::zeros(2, torch::kDouble)).sum(-1);
  EXPECT_NEAR((log_q - log_p).mean().item<double>(),
              kl_to_standard_normal(mean, log_std).item<double>(), 0.02);
}

TEST(GaussianTest, LogProbIsTheNormalDensity) {
  const double x = 0.3, m = -0.2, log_s = 0.25, s = std::exp(log_s);
  const double expected =
      std::log(std::exp(-0.5 * (x - m) * (x - m) / (s * s)) / (s * std::sqrt(2 * M_PI)));
  const auto got = gaussian_log_prob(torch::tensor(x, torch::kDouble), torch::tensor(m, torch::kDouble),
                                     torch::tensor(log_s, torch::kDouble));
  EXPECT_NEAR(got.item<double>(), expected, 1e-12);
}

TEST(GaussianTest, SoftBoundStaysInsideAndIsSmooth) {
  const auto raw = torch::linspace(-100, 100, 101);
  const auto y = soft_bound(raw, -5, 2);
  EXPECT_GE(y.min().item<double>(), -5.0);
  EXPECT_LE(y.max().item<double>(), 2.0);
  EXPECT_NEAR(soft_bound(torch::tensor(0.0), -5, 2).item<double>(), -1.5, 1e-6);
}

}  // namespace
}  // namespace vaegail::vae
