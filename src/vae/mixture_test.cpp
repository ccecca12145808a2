#include "vae/mixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vaegail::vae {
namespace {

// log sum_k w_k N(x | m_k, s_k^2) with plain loops in double (log-sum-exp by hand).
double direct_log_prob(double x, const std::vector<double>& logits,
                       const std::vector<double>& means, const std::vector<double>& log_stds) {
  double max_logit = -INFINITY;
  for (double l : logits) max_logit = std::max(max_logit, l);
  double z = 0;
  for (double l : logits) z += std::exp(l - max_logit);
  std::vector<double> terms;
  double max_term = -INFINITY;
  for (size_t k = 0; k < logits.size(); ++k) {
    const double log_w = logits[k] - max_logit - std::log(z);
    const double s = std::exp(log_stds[k]);
    const double log_n = -0.5 * (x - means[k]) * (x - means[k]) / (s * s) - log_stds[k] -
                         0.5 * std::log(2 * M_PI);
    terms.push_back(log_w + log_n);
    max_term = std::max(max_term, terms.back());
  }
  double sum = 0;
  for (double t : terms) sum += std::exp(t - max_term);
  return max_term + std::log(sum);
}

std::vector<double> row(const torch::Tensor& t, int64_t i) {
  const auto r = t[i].to(torch::kDouble).contiguous();
  return std::vector<double>(r.data_ptr<double>(), r.data_ptr<double>() + r.numel());
}

TEST(MixtureTest, LogProbMatchesPlainLoops) {
  torch::manual_seed(3);
  const int64_t N = 50, K = 4;
  MixtureParams m{2 * torch::randn({N, K}), 3 * torch::randn({N, K}), torch::randn({N, K})};
  const auto x = 3 * torch::randn({N});
  const auto got = mixture_log_prob(x, m);
  ASSERT_EQ(got.sizes(), torch::IntArrayRef({N}));
  for (int64_t i = 0; i < N; ++i) {
    const double expected = direct_log_prob(x[i].item<double>(), row(m.logits, i),
                                            row(m.means, i), row(m.log_stds, i));
    EXPECT_NEAR(got[i].item<double>(), expected, 1e-4 * (1 + std::abs(expected))) << i;
  }
}

TEST(MixtureTest, StableFarFromEveryComponent) {
  // Every component's density underflows in float (and double) for x = 1e4, std 0.01;
  // the log-density is still finite and right.
  MixtureParams m{torch::tensor({{0.0f, 1.0f}}), torch::tensor({{0.0f, 1.0f}}),
                  torch::tensor({{-4.6f, -4.6f}})};
  const auto got = mixture_log_prob(torch::tensor({1e4f}), m);
  EXPECT_TRUE(torch::isfinite(got).all().item<bool>());
  const double expected = direct_log_prob(1e4, {0, 1}, {0, 1}, {-4.6, -4.6});
  EXPECT_NEAR(got.item<double>(), expected, 1e-5 * std::abs(expected));
  // And gradients stay finite too.
  auto means = m.means.clone().requires_grad_(true);
  mixture_log_prob(torch::tensor({1e4f}), {m.logits, means, m.log_stds}).sum().backward();
  EXPECT_TRUE(torch::isfinite(means.grad()).all().item<bool>());
}

TEST(MixtureTest, OneComponentIsAGaussian) {
  MixtureParams m{torch::zeros({1, 1}), torch::full({1, 1}, 2.0), torch::full({1, 1}, 0.5)};
  const double s = std::exp(0.5);
  const double expected = -0.5 * (1.0 - 2.0) * (1.0 - 2.0) / (s * s) - 0.5 - 0.5 * std::log(2 * M_PI);
  EXPECT_NEAR(mixture_log_prob(torch::ones({1}), m).item<double>(), expected, 1e-6);
}

TEST(MixtureTest, SamplesFollowWeightsMeansAndStds) {
  const int64_t N = 40000;
  MixtureParams m{torch::log(torch::tensor({0.3f, 0.7f})).expand({N, 2}),
                  torch::tensor({-10.0f, 10.0f}).expand({N, 2}),
                  torch::log(torch::tensor({1.0f, 2.0f})).expand({N, 2})};
  auto gen = at::detail::createCPUGenerator(5);
  const auto x = mixture_sample(m, gen);
  ASSERT_EQ(x.sizes(), torch::IntArrayRef({N}));
  const auto right = x > 0;
  EXPECT_NEAR(right.to(torch::kDouble).mean().item<double>(), 0.7, 0.01);
  EXPECT_NEAR(x.index({right}).mean().item<double>(), 10.0, 0.05);
  EXPECT_NEAR(x.index({right}).std().item<double>(), 2.0, 0.05);
  EXPECT_NEAR(x.index({~right}).mean().item<double>(), -10.0, 0.05);
  EXPECT_NEAR(x.index({~right}).std().item<double>(), 1.0, 0.05);
  auto gen2 = at::detail::createCPUGenerator(5);
  EXPECT_TRUE(torch::equal(x, mixture_sample(m, gen2)));
}

}  // namespace
}  // namespace vaegail::vae
