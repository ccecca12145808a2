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

}  // namespace
}  // namespace vaegail::vae
