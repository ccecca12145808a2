#include "gail/residual_policy.h"

#include <gtest/gtest.h>

#include "gail/test_support.h"
#include "rl/trpo.h"

namespace vaegail {
namespace {

constexpr int kObsDim = 4, kActDim = 2, kLatentDim = 3;

class ResidualPolicyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::manual_seed(5);
    base = vae::TrajectoryVae(tiny_vae_config(kObsDim, kActDim, kLatentDim));
    // Non-trivial statistics on both sides, so that an error in (de)normalising shows.
    base->set_normalization(torch::tensor({1.f, -2.f, 0.5f, 3.f}), torch::tensor({2.f, 0.5f, 1.f, 4.f}),
                            torch::tensor({0.3f, -0.1f}), torch::tensor({0.7f, 2.f}));
    normalizer = std::make_shared<ObsNormalizer>(kObsDim);
    const auto sample = [](int64_t n) { return torch::randn({n, kObsDim}) * torch::tensor({3.f, 0.2f, 1.f, 5.f}) + 2.0; };
    normalizer->update(sample(200));
    normalizer->set_frozen(true);
    policy = std::make_shared<ResidualPolicy>(base, normalizer);
    raw = sample(16);  // within the normaliser's clip, where its inverse is exact
    z = torch::randn({16, kLatentDim});
    input = torch::cat({normalizer->normalize(raw), z}, -1);
  }

  torch::Tensor parameter(const std::string& name) { return policy->named_parameters()[name]; }

  vae::TrajectoryVae base{nullptr};
  std::shared_ptr<ObsNormalizer> normalizer;
  std::shared_ptr<ResidualPolicy> policy;
  torch::Tensor raw, z, input;
};

TEST_F(ResidualPolicyTest, IsTheVaeMeanWhenTheResidualOutputIsZero) {
  {
    torch::NoGradGuard no_grad;
    parameter("residual.layer2.weight").zero_();
    parameter("residual.layer2.bias").zero_();
  }
  const auto dist = policy->distribution(input);
  torch::NoGradGuard no_grad;
  EXPECT_TRUE(torch::allclose(dist.mean, base->action_mean(raw, z), 1e-4, 1e-5));
  EXPECT_TRUE(torch::allclose(dist.log_std, torch::full({16, kActDim}, -1.0)));
  EXPECT_EQ(policy->input_dim(), kObsDim + kLatentDim);
  EXPECT_EQ(policy->act_dim(), kActDim);
}

TEST_F(ResidualPolicyTest, StartsCloseToTheVaeMean) {
  torch::NoGradGuard no_grad;
  const auto gap = (policy->distribution(input).mean - base->action_mean(raw, z)).abs().max().item<double>();
  EXPECT_LT(gap, 0.15);
  EXPECT_GT(gap, 0.0);  // near 0, not 0: the residual's hidden layers still get gradient
}

TEST_F(ResidualPolicyTest, GradientsStopAtTheVae) {
  policy->distribution(input).log_prob(torch::randn({16, kActDim})).sum().backward();
  for (const auto& p : base->parameters()) {
    EXPECT_FALSE(p.requires_grad());
    EXPECT_FALSE(p.grad().defined());
  }
  int64_t trainable = 0, residual = 0;
  for (const auto& p : policy->trainable_parameters()) {
    trainable += p.numel();
    EXPECT_TRUE(p.grad().defined());
  }
  for (const auto& item : policy->named_parameters())
    if (item.key().rfind("residual.", 0) == 0 || item.key() == "log_std") residual += item.value().numel();
  EXPECT_EQ(trainable, residual);
}

TEST_F(ResidualPolicyTest, TrpoMovesTheResidualAndLeavesTheVaeAlone) {
  std::vector<torch::Tensor> before;
  for (const auto& p : base->parameters()) before.push_back(p.clone());
  const auto residual_before = parameter("residual.layer2.weight").clone();
  CriticOptions c;
  c.input_dim = kObsDim + kLatentDim;
  c.hidden = {8};
  Trpo trpo(policy, std::make_shared<Critic>(c));
  torch::Tensor actions, old_log_probs;
  {
    torch::NoGradGuard no_grad;
    actions = base->action_mean(raw, z) + 0.3;
    old_log_probs = policy->distribution(input).log_prob(actions);
  }
  const UpdateBatch batch{input, actions, old_log_probs, torch::randn({16}), torch::zeros({16})};
  ASSERT_TRUE(trpo.update(batch).accepted);
  const auto parameters = base->parameters();
  for (size_t i = 0; i < parameters.size(); ++i) EXPECT_TRUE(torch::equal(parameters[i], before[i]));
  EXPECT_FALSE(torch::equal(parameter("residual.layer2.weight"), residual_before));
}

}  // namespace
}  // namespace vaegail
