#include "eval/tsne.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "util/rng.h"

namespace vaegail::eval {
namespace {

std::vector<double> gaussian_points(int n, int d, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<double> x(static_cast<size_t>(n) * d);
  for (double& v : x) v = rng.normal();
  return x;
}

TEST(Tsne, CalibratedRowsHaveEntropyLogPerplexity) {
  const int n = 60, d = 4;
  // Points at very different scales, so a fixed bandwidth would not do.
  auto x = gaussian_points(n, d, 1);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < d; ++k) x[i * d + k] *= (i % 3 == 0 ? 100.0 : i % 3 == 1 ? 1.0 : 0.01);
  for (double perplexity : {2.0, 10.0, 30.0}) {
    const auto p = conditional_probabilities(squared_distances(x, n, d), n, perplexity);
    for (int i = 0; i < n; ++i) {
      double sum = 0, entropy = 0;
      for (int j = 0; j < n; ++j) {
        const double v = p[i * n + j];
        sum += v;
        if (v > 0) entropy -= v * std::log(v);
      }
      EXPECT_EQ(p[i * n + i], 0.0);
      EXPECT_NEAR(sum, 1.0, 1e-12);
      EXPECT_NEAR(entropy, std::log(perplexity), 1e-6) << "row " << i << ", perplexity " << perplexity;
    }
  }
}

TEST(Tsne, JointProbabilitiesAreSymmetricAndSumToOne) {
  const int n = 20, d = 3;
  const auto p = joint_probabilities(
      conditional_probabilities(squared_distances(gaussian_points(n, d, 2), n, d), n, 5), n);
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      sum += p[i * n + j];
      EXPECT_DOUBLE_EQ(p[i * n + j], p[j * n + i]);
    }
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

TEST(Tsne, GradientMatchesFiniteDifferencesOfKl) {
  const int n = 7, d = 3;
  const auto p = joint_probabilities(
      conditional_probabilities(squared_distances(gaussian_points(n, d, 3), n, d), n, 3), n);
  auto y = gaussian_points(n, 2, 4);
  const auto gradient = kl_gradient(p, y, n);
  const double h = 1e-6;
  for (size_t k = 0; k < y.size(); ++k) {
    auto plus = y, minus = y;
    plus[k] += h;
    minus[k] -= h;
    const double numeric = (kl_divergence(p, plus, n) - kl_divergence(p, minus, n)) / (2 * h);
    EXPECT_NEAR(gradient[k], numeric, 1e-7 + 1e-5 * std::abs(numeric)) << "coordinate " << k;
  }
  // Exaggeration scales only the attractive (P) part.
  const auto attract = kl_gradient(p, y, n, 2.0);
  const auto zero_p = kl_gradient(std::vector<double>(p.size(), 0.0), y, n);
  for (size_t k = 0; k < y.size(); ++k)
    EXPECT_NEAR(attract[k], 2 * gradient[k] - zero_p[k], 1e-12);
}

// Fraction of points whose 5 nearest neighbours (in the embedding) mostly share their label.
double five_nn_agreement(const std::vector<double>& y, const std::vector<int>& labels) {
  const int n = static_cast<int>(labels.size());
  int agree = 0;
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> by_distance;
    for (int j = 0; j < n; ++j)
      if (j != i) by_distance.push_back({std::hypot(y[2 * i] - y[2 * j], y[2 * i + 1] - y[2 * j + 1]), j});
    std::partial_sort(by_distance.begin(), by_distance.begin() + 5, by_distance.end());
    int same = 0;
    for (int k = 0; k < 5; ++k) same += labels[by_distance[k].second] == labels[i];
    agree += same >= 3;
  }
  return static_cast<double>(agree) / n;
}

TEST(Tsne, SeparatedClustersStaySeparated) {
  const int clusters = 4, per = 40, n = clusters * per, d = 10;
  auto x = gaussian_points(n, d, 5);
  std::vector<int> labels(n);
  for (int i = 0; i < n; ++i) {
    labels[i] = i % clusters;
    x[i * d + labels[i]] += 12.0;  // cluster c is shifted along axis c
  }
  TsneOptions options;
  options.perplexity = 15;
  options.iterations = 400;
  const auto result = tsne(x, n, d, options);
  ASSERT_EQ(result.embedding.size(), static_cast<size_t>(n) * 2);
  EXPECT_GE(five_nn_agreement(result.embedding, labels), 0.95);
  EXPECT_LT(result.kl_divergence, 1.5);
  // A random layout keeps no structure: the measure itself is not trivially satisfied.
  EXPECT_LT(five_nn_agreement(gaussian_points(n, 2, 6), labels), 0.6);
}

TEST(Tsne, SameSeedSameLayoutOtherSeedOther) {
  const int n = 40, d = 5;
  const auto x = gaussian_points(n, d, 7);
  TsneOptions options;
  options.perplexity = 8;
  options.iterations = 100;
  const auto a = tsne(x, n, d, options), b = tsne(x, n, d, options);
  EXPECT_EQ(a.embedding, b.embedding);
  options.seed = 1;
  EXPECT_NE(tsne(x, n, d, options).embedding, a.embedding);
}

TEST(Tsne, RejectsBadInput) {
  const auto x = gaussian_points(10, 2, 8);
  TsneOptions options;  // perplexity 30 needs more than 31 points
  EXPECT_THROW(tsne(x, 10, 2, options), std::invalid_argument);
  options.perplexity = 3;
  EXPECT_THROW(tsne(x, 10, 3, options), std::invalid_argument);
  auto with_nan = x;
  with_nan[5] = NAN;
  EXPECT_THROW(tsne(with_nan, 10, 2, options), std::invalid_argument);
  EXPECT_NO_THROW(tsne(x, 10, 2, options));
}

}  // namespace
}  // namespace vaegail::eval
