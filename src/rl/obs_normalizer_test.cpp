#include "rl/obs_normalizer.h"

#include <gtest/gtest.h>

#include "rl/test_support.h"

namespace vaegail {
namespace {

TEST(ObsNormalizer, MergedBatchMomentsEqualTheMomentsOfAllData) {
  torch::manual_seed(3);
  const auto data = torch::randn({1000, 4}, torch::kFloat64) * torch::tensor({1.0, 10.0, 0.1, 3.0}, torch::kFloat64) +
                    torch::tensor({5.0, -2.0, 0.0, 100.0}, torch::kFloat64);
  ObsNormalizer normalizer(4);
  for (const auto& part : {data.slice(0, 0, 1), data.slice(0, 1, 301), data.slice(0, 301, 307), data.slice(0, 307)})
    normalizer.update(part);
  EXPECT_DOUBLE_EQ(normalizer.count(), 1000.0);
  EXPECT_TRUE(torch::allclose(normalizer.mean(), data.mean(0), 1e-12, 1e-12));
  EXPECT_TRUE(torch::allclose(normalizer.var(), data.var(0, /*unbiased=*/false), 1e-12, 1e-12));
}

TEST(ObsNormalizer, NormalisesClipsAndIgnoresUpdatesWhenFrozen) {
  ObsNormalizer normalizer(2, /*clip=*/3.0);
  normalizer.update(torch::tensor({{1.0f, 10.0f}, {3.0f, 30.0f}}));  // mean (2, 20), std (1, 10)
  const auto z = normalizer.normalize(torch::tensor({{2.5f, 0.0f}, {100.0f, 20.0f}}));
  EXPECT_EQ(z.scalar_type(), torch::kFloat32);
  EXPECT_TRUE(torch::allclose(z, torch::tensor({{0.5f, -2.0f}, {3.0f, 0.0f}}), 1e-5, 1e-5));
  normalizer.set_frozen(true);
  normalizer.update(torch::tensor({{100.0f, 100.0f}}));
  EXPECT_DOUBLE_EQ(normalizer.count(), 2.0);
  EXPECT_NEAR(normalizer.mean()[0].item<double>(), 2.0, 1e-12);
}

}  // namespace
}  // namespace vaegail
