#include "util/numerical_fault.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace vaegail {
namespace {

std::string fault_of(double value) {
  try {
    require_finite(value, "vae train: epoch 3, batch 7: loss");
  } catch (const NumericalFault& e) {
    return e.what();
  }
  return "";
}

TEST(NumericalFault, AFiniteValuePassesThrough) { EXPECT_EQ(require_finite(-2.5, "loss"), -2.5); }

TEST(NumericalFault, ANonFiniteValueIsOneLineNamingItAndWhere) {
  EXPECT_EQ(fault_of(std::numeric_limits<double>::quiet_NaN()), "vae train: epoch 3, batch 7: loss is nan");
  EXPECT_EQ(fault_of(std::numeric_limits<double>::infinity()), "vae train: epoch 3, batch 7: loss is inf");
  EXPECT_EQ(fault_of(-std::numeric_limits<double>::infinity()), "vae train: epoch 3, batch 7: loss is -inf");
}

TEST(NumericalFault, AStateIsFiniteOnlyWhenEveryValueIs) {
  std::vector<float> state = {0.f, 1e30f, -3.f};
  EXPECT_TRUE(all_finite(state.data(), state.size()));
  state[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(all_finite(state.data(), state.size()));
  const double diverged[] = {1.0, -std::numeric_limits<double>::infinity()};
  EXPECT_FALSE(all_finite(diverged, 2));
  EXPECT_TRUE(all_finite(diverged, 1));
}

}  // namespace
}  // namespace vaegail
