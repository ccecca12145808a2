#include "rl/gae.h"

#include <gtest/gtest.h>

#include "rl/test_support.h"

namespace vaegail {
namespace {

// Columns are environments: env 0 runs on, env 1 terminates at t=0 and is truncated at t=1.
TEST(Gae, MatchesAHandComputedExampleWithTerminationAndTruncation) {
  const double gamma = 0.9, lambda = 0.8;
  const auto rewards = torch::tensor({{1.0, 1.0}, {2.0, 1.0}, {3.0, 1.0}});
  const auto values = torch::tensor({{0.5, 0.2}, {1.0, 0.4}, {1.5, 0.6}});
  const auto next_values = torch::tensor({{1.0, 7.0}, {1.5, 5.0}, {2.0, 2.0}});
  const auto terminated = torch::tensor({{0.0, 1.0}, {0.0, 0.0}, {0.0, 0.0}});
  const auto truncated = torch::tensor({{0.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}});
  const auto out = compute_gae(rewards, values, next_values, terminated, truncated, gamma, lambda);

  // env 0: δ = (1 + 0.9·1 − 0.5, 2 + 0.9·1.5 − 1, 3 + 0.9·2 − 1.5) = (1.4, 2.35, 3.3), γλ = 0.72
  // env 1: t=0 terminated: δ = 1 − 0.2, no bootstrap, trace cut; t=1 truncated: δ = 1 + 0.9·5 − 0.4
  //        bootstraps from V(final observation) = 5, trace cut; t=2: δ = 1 + 0.9·2 − 0.6.
  const auto expected = torch::tensor({{1.4 + 0.72 * (2.35 + 0.72 * 3.3), 0.8},
                                       {2.35 + 0.72 * 3.3, 5.1},
                                       {3.3, 2.2}});
  EXPECT_TRUE(torch::allclose(out.advantages, expected, 1e-6, 1e-6)) << out.advantages;
  EXPECT_TRUE(torch::allclose(out.returns, expected + values, 1e-6, 1e-6));
}

TEST(Gae, LambdaOneGivesDiscountedReturnsMinusValues) {
  const auto rewards = torch::tensor({{1.0}, {0.0}, {2.0}, {1.0}});
  const auto values = torch::tensor({{0.3}, {0.1}, {0.4}, {0.2}});
  const auto next_values = torch::tensor({{0.1}, {0.4}, {0.2}, {10.0}});
  const auto zeros = torch::zeros({4, 1});
  const auto out = compute_gae(rewards, values, next_values, zeros, zeros, 0.5, 1.0);
  // Return from t=0: 1 + 0.5·0 + 0.25·2 + 0.125·1 + 0.0625·10 (the bootstrap at the end).
  EXPECT_NEAR(out.returns[0][0].item<double>(), 1 + 0.5 + 0.125 + 0.625, 1e-6);
  EXPECT_NEAR(out.advantages[3][0].item<double>(), 1 + 5 - 0.2, 1e-6);
}

}  // namespace
}  // namespace vaegail
