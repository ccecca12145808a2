#include "util/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace vaegail {
namespace {

TEST(Rng, DerivedSeedsDifferPerStreamAndRepeatPerSeed) {
  std::set<std::uint64_t> seen;
  for (std::uint64_t s = 0; s < 100; ++s) seen.insert(derive_seed(42, s));
  EXPECT_EQ(seen.size(), 100u);
  EXPECT_EQ(derive_seed(7, 3), derive_seed(7, 3));
  EXPECT_NE(derive_seed(7, 3), derive_seed(8, 3));
}

TEST(Rng, UniformAndNormalHaveTheirMoments) {
  Rng rng(1);
  const int n = 200000;
  double su = 0, sn = 0, sn2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u;
    const double z = rng.normal();
    sn += z;
    sn2 += z * z;
  }
  EXPECT_NEAR(su / n, 0.5, 0.005);
  EXPECT_NEAR(sn / n, 0.0, 0.01);
  EXPECT_NEAR(sn2 / n, 1.0, 0.01);
}

TEST(Rng, SameSeedSameSequence) {
  Rng a(99), b(99);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(a.next(), b.next());
}

}  // namespace
}  // namespace vaegail

namespace vaegail {
namespace {

TEST(EpisodeStreams, EachEpisodeDrawsItsOwnSeededStreamWhateverTheOrder) {
  EpisodeStreams forward(9), backward(9);
  const double a0 = forward(0).normal(), a1 = forward(1).normal();
  const double b1 = backward(1).normal(), b0 = backward(0).normal();
  EXPECT_EQ(a0, b0);
  EXPECT_EQ(a1, b1);
  EXPECT_NE(a0, a1);
  EXPECT_EQ(a0, Rng(derive_seed(9, 0)).normal());
  EXPECT_EQ(forward(0).normal(), backward(0).normal());  // a stream continues where it was
}

}  // namespace
}  // namespace vaegail
