#include "vae/trajectory_encoder.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace vaegail::vae {
namespace {

class TrajectoryEncoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::set_num_threads(1);
    torch::manual_seed(4);
  }
};

TEST_F(TrajectoryEncoderTest, Shapes) {
  TrajectoryEncoder enc(5, 8, 3);
  const auto q = enc->forward(torch::randn({4, 11, 5}));
  EXPECT_EQ(q.mean.sizes(), torch::IntArrayRef({4, 3}));
  EXPECT_EQ(q.log_std.sizes(), torch::IntArrayRef({4, 3}));
  EXPECT_EQ(enc->pooled_features(torch::randn({4, 11, 5})).sizes(), torch::IntArrayRef({4, 16}));
}

TEST_F(TrajectoryEncoderTest, PoolsTheMeanOfAllSecondLayerOutputs) {
  TrajectoryEncoder enc(5, 8, 3);
  const auto x = torch::randn({2, 9, 5});
  const auto outputs = enc->lstm()->forward(x, torch::full({2}, 9, torch::kLong));  // [2, 9, 16]
  EXPECT_TRUE(torch::allclose(enc->pooled_features(x), outputs.mean(1), 1e-6, 1e-6));
}

TEST_F(TrajectoryEncoderTest, MaskedStepsAreIgnored) {
  // Row 0 is 6 real steps then 4 padding steps of large values; row 1 is full. Each row must
  // encode exactly as it does alone and unpadded.
  TrajectoryEncoder enc(5, 8, 3);
  const auto a = torch::randn({1, 6, 5}), b = torch::randn({1, 10, 5});
  const auto padded = torch::cat({torch::cat({a, torch::full({1, 4, 5}, 1e3)}, 1), b});
  auto mask = torch::ones({2, 10}, torch::kBool);
  mask.index_put_({0, torch::indexing::Slice(6)}, false);
  const auto both = enc->forward(padded, mask);
  const auto alone_a = enc->forward(a), alone_b = enc->forward(b);
  EXPECT_TRUE(torch::allclose(both.mean[0], alone_a.mean[0], 1e-5, 1e-5));
  EXPECT_TRUE(torch::allclose(both.log_std[0], alone_a.log_std[0], 1e-5, 1e-5));
  EXPECT_TRUE(torch::allclose(both.mean[1], alone_b.mean[0], 1e-5, 1e-5));
  // And the padding does matter when the mask is dropped (the test can fail).
  EXPECT_FALSE(torch::allclose(enc->forward(padded).mean[0], alone_a.mean[0], 1e-3, 1e-3));
}

TEST_F(TrajectoryEncoderTest, GradientsFlowThroughThePackedPath) {
  TrajectoryEncoder enc(3, 4, 2);
  const auto x = torch::randn({2, 5, 3});
  auto mask = torch::ones({2, 5}, torch::kBool);
  mask.index_put_({1, torch::indexing::Slice(2)}, false);
  enc->forward(x, mask).mean.sum().backward();
  for (const auto& p : enc->parameters()) {
    ASSERT_TRUE(p.grad().defined());
    EXPECT_TRUE(torch::isfinite(p.grad()).all().item<bool>());
  }
}

TEST_F(TrajectoryEncoderTest, MaskMustBeANonEmptyPrefix) {
  EXPECT_TRUE(torch::equal(mask_lengths(torch::tensor({{1, 1, 0}, {1, 1, 1}})), torch::tensor({2, 3}, torch::kLong)));
  EXPECT_THROW(mask_lengths(torch::tensor({{1, 0, 1}})), std::invalid_argument);
  EXPECT_THROW(mask_lengths(torch::tensor({{0, 0, 0}})), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail::vae
