#include "vae/state_decoder.h"

#include <gtest/gtest.h>

#include "vae/mixture.h"

namespace vaegail::vae {
namespace {

StateDecoderOptions small_options(int64_t D = 7, int64_t layers = 4) {
  StateDecoderOptions o;
  o.state_dim = D;
  o.cond_dim = D + 3;
  o.channels = 8;
  o.layers = layers;
  o.components = 3;
  return o;
}

struct Batch {
  torch::Tensor prev, next, z;
};

Batch random_batch(const StateDecoderOptions& o, int64_t N) {
  return {torch::randn({N, o.state_dim}), torch::randn({N, o.state_dim}),
          torch::randn({N, o.cond_dim - o.state_dim})};
}

// Non-zero position biases, so the test sees them.
void perturb_biases(StateDecoderImpl& decoder) {
  torch::NoGradGuard no_grad;
  for (auto& p : decoder.named_parameters())
    if (p.key().find("bias") != std::string::npos) p.value().normal_(0.0, 0.3);
}

class StateDecoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::set_num_threads(1);
    torch::manual_seed(7);
  }
};

TEST_F(StateDecoderTest, DilationsDoubleAndWrapModuloLog2D) {
  EXPECT_EQ(wavenet_dilations(6, 18), (std::vector<int64_t>{1, 2, 4, 8, 16, 1}));
  EXPECT_EQ(wavenet_dilations(4, 16), (std::vector<int64_t>{1, 2, 4, 8}));
  EXPECT_EQ(wavenet_dilations(3, 2), (std::vector<int64_t>{1, 1, 1}));
  EXPECT_EQ(wavenet_dilations(2, 1), (std::vector<int64_t>{1, 1}));
  const auto humanoid = wavenet_dilations(14, 130);
  EXPECT_EQ(humanoid[7], 128);
  EXPECT_EQ(humanoid[8], 1);
  EXPECT_EQ(humanoid[13], 32);
}

TEST_F(StateDecoderTest, OutputShapes) {
  const auto o = small_options();
  StateDecoder decoder(o);
  const auto b = random_batch(o, 5);
  const auto m = decoder->forward(b.prev, b.next, b.z);
  EXPECT_EQ(m.logits.sizes(), torch::IntArrayRef({5, 7, 3}));
  EXPECT_EQ(m.means.sizes(), torch::IntArrayRef({5, 7, 3}));
  EXPECT_EQ(m.log_stds.sizes(), torch::IntArrayRef({5, 7, 3}));
  EXPECT_EQ(decoder->log_prob(b.prev, b.next, b.z).sizes(), torch::IntArrayRef({5, 7}));
}

// Both paths, forward and every gradient, on shapes that exercise chunk borders (N not a
// multiple of the chunk), every dilation and the wrap-around, with and without positions.
void expect_kernel_matches_reference(bool position_embedding, int64_t chunk_positions) {
  auto o = small_options(11, 6);  // dilations 1 2 4 8 1 2
  o.position_embedding = position_embedding;
  StateDecoder decoder(o);
  perturb_biases(*decoder);
  const auto b = random_batch(o, 37);
  auto z_fast = b.z.clone().requires_grad_(true), z_ref = b.z.clone().requires_grad_(true);
  ASSERT_TRUE(decoder->uses_kernel(b.next));

  set_wavenet_chunk_positions(chunk_positions);
  const auto fast = decoder->forward(b.prev, b.next, z_fast);
  set_wavenet_chunk_positions(0);
  const auto ref = decoder->forward_reference(b.prev, b.next, z_ref);
  EXPECT_TRUE(torch::allclose(fast.logits, ref.logits, 1e-5, 1e-5));
  EXPECT_TRUE(torch::allclose(fast.means, ref.means, 1e-5, 1e-5));
  EXPECT_TRUE(torch::allclose(fast.log_stds, ref.log_stds, 1e-5, 1e-5));
  EXPECT_LT((fast.means - ref.means).abs().max().item<double>(), 1e-5);

  // A loss that weights every output differently.
  const auto weights = torch::randn(fast.means.sizes());
  auto loss = [&](const MixtureParams& m) {
    return ((m.logits + 2 * m.means + 3 * m.log_stds) * weights).sum();
  };
  auto params = decoder->parameters();
  std::vector<torch::Tensor> inputs(params.begin(), params.end());
  inputs.push_back(z_fast);
  set_wavenet_chunk_positions(chunk_positions);
  const auto g_fast = torch::autograd::grad({loss(fast)}, inputs);
  set_wavenet_chunk_positions(0);
  inputs.back() = z_ref;
  const auto g_ref = torch::autograd::grad({loss(ref)}, inputs);
  const auto names = decoder->named_parameters().keys();
  for (size_t i = 0; i < g_fast.size(); ++i) {
    const std::string name = i < names.size() ? names[i] : "z";
    const double scale = 1.0 + g_ref[i].abs().max().item<double>();
    EXPECT_LT((g_fast[i] - g_ref[i]).abs().max().item<double>(), 1e-5 * scale) << name;
  }
}

TEST_F(StateDecoderTest, KernelMatchesConv1dReferenceWithPositions) {
  expect_kernel_matches_reference(true, 4);
}

TEST_F(StateDecoderTest, KernelMatchesConv1dReferenceSharedBias) {
  expect_kernel_matches_reference(false, 0);
}

TEST_F(StateDecoderTest, KernelMatchesReferenceWithTwoThreads) {
  torch::set_num_threads(2);
  expect_kernel_matches_reference(true, 3);
  torch::set_num_threads(1);
}

// Component k's distribution depends on x_{t+1}[0..k-1] only: changing components >= k
// leaves it unchanged, changing one component < k changes it.
void expect_causal(bool use_kernel) {
  const auto o = small_options(9, 5);  // dilations 1 2 4 8 1: receptive field covers D
  StateDecoder decoder(o);
  perturb_biases(*decoder);
  torch::NoGradGuard no_grad;
  const auto b = random_batch(o, 4);
  auto run = [&](const torch::Tensor& next) {
    return use_kernel ? decoder->forward(b.prev, next, b.z)
                      : decoder->forward_reference(b.prev, next, b.z);
  };
  const auto base = run(b.next);
  for (int64_t k = 0; k < o.state_dim; ++k) {
    auto later = b.next.clone();
    later.narrow(1, k, o.state_dim - k).add_(torch::randn({4, o.state_dim - k}));
    const auto m = run(later);
    for (int64_t j = 0; j <= k; ++j) {
      EXPECT_TRUE(torch::equal(m.means.select(1, j), base.means.select(1, j)))
          << "component " << j << " saw a change at >= " << k;
      EXPECT_TRUE(torch::equal(m.logits.select(1, j), base.logits.select(1, j)));
      EXPECT_TRUE(torch::equal(m.log_stds.select(1, j), base.log_stds.select(1, j)));
    }
    for (int64_t j = 0; j < k; ++j) {  // a change at j < k reaches k
      auto earlier = b.next.clone();
      earlier.select(1, j).add_(1.0);
      const auto e = run(earlier);
      EXPECT_GT((e.means.select(1, k) - base.means.select(1, k)).abs().max().item<double>(),
                1e-6)
          << "component " << k << " does not see component " << j;
    }
  }
}

TEST_F(StateDecoderTest, KernelIsCausalOverComponents) { expect_causal(true); }
TEST_F(StateDecoderTest, ReferenceIsCausalOverComponents) { expect_causal(false); }

TEST_F(StateDecoderTest, PositionEmbeddingSeparatesComponents) {
  // Same input at every component (zeros), zero weights except the position bias: only
  // P_l[k] can make the components' distributions differ.
  const auto o = small_options(6, 3);
  StateDecoder decoder(o);
  {
    torch::NoGradGuard no_grad;
    for (auto& p : decoder->parameters()) p.zero_();
    decoder->named_parameters()["gate_bias"].normal_();
    decoder->named_parameters()["out_weight"].normal_();
    decoder->named_parameters()["head_hidden.weight"].normal_();
    decoder->named_parameters()["head_out.weight"].normal_();
  }
  const auto b = random_batch(o, 2);
  const auto m = decoder->forward(b.prev, torch::zeros({2, 6}), b.z);
  EXPECT_GT((m.means.select(1, 3) - m.means.select(1, 4)).abs().max().item<double>(), 1e-4);
}

TEST_F(StateDecoderTest, SamplesFollowTheAutoregressiveModel) {
  const auto o = small_options(4, 2);
  StateDecoder decoder(o);
  const auto b = random_batch(o, 3);
  auto gen = at::detail::createCPUGenerator(11);
  const auto x = decoder->sample(b.prev, b.z, gen);
  EXPECT_EQ(x.sizes(), torch::IntArrayRef({3, 4}));
  EXPECT_TRUE(torch::isfinite(x).all().item<bool>());
  auto gen2 = at::detail::createCPUGenerator(11);
  EXPECT_TRUE(torch::equal(x, decoder->sample(b.prev, b.z, gen2)));
}

}  // namespace
}  // namespace vaegail::vae
