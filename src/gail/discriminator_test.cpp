#include "gail/discriminator.h"

#include <gtest/gtest.h>

#include "gail/test_support.h"

namespace vaegail {
namespace {

constexpr int kObs = 3, kAct = 2;

DiscriminatorOptions options(int latent_dim) {
  DiscriminatorOptions o;
  o.obs_dim = kObs;
  o.act_dim = kAct;
  o.latent_dim = latent_dim;
  return o;
}

// (x, a) ~ N(mean, I) with z given per sample.
DiscriminatorData gaussian(int64_t n, const torch::Tensor& mean, const torch::Tensor& z) {
  return {torch::randn({n, kObs}) + mean.slice(-1, 0, kObs), torch::randn({n, kAct}) + mean.slice(-1, kObs), z};
}

// Full-batch training, the shuffle's generator unused.
DiscriminatorStats train_full_batch(DiscriminatorTrainer& trainer, const DiscriminatorData& demos,
                                    const DiscriminatorData& policy, int steps) {
  auto unused = at::detail::createCPUGenerator(0);
  return trainer.train(demos, policy, steps, 1, unused);
}

DiscriminatorData rows_of(const DiscriminatorData& d, const torch::Tensor& rows) {
  return {d.observations.index_select(0, rows), d.actions.index_select(0, rows), d.z.index_select(0, rows)};
}

torch::Tensor no_z(int64_t n) { return torch::zeros({n, 0}); }

class DiscriminatorTest : public ::testing::Test {
 protected:
  void SetUp() override { torch::manual_seed(3); }
};

TEST_F(DiscriminatorTest, SeparatesTwoGaussiansWithinAFewHundredSteps) {
  // Means 2 apart in each of 5 dimensions: the Bayes classifier is right 98.7% of the time.
  const auto up = torch::ones({kObs + kAct}), down = -torch::ones({kObs + kAct});
  auto d = std::make_shared<Discriminator>(options(0));
  const auto demos = gaussian(512, up, no_z(512)), policy = gaussian(512, down, no_z(512));
  d->fit_normalization(demos.observations, demos.actions);
  DiscriminatorTrainer trainer(d, 1e-3);
  const double loss_before = evaluate_discriminator(*d, demos, policy).loss;
  train_full_batch(trainer, demos, policy, 200);
  const auto fresh = evaluate_discriminator(*d, gaussian(2000, up, no_z(2000)), gaussian(2000, down, no_z(2000)));
  EXPECT_GT(fresh.demo_accuracy, 0.95);
  EXPECT_GT(fresh.policy_accuracy, 0.95);
  EXPECT_LT(fresh.loss, 0.25);
  EXPECT_LT(fresh.loss, loss_before);
}

TEST_F(DiscriminatorTest, TrainReportsTheStateBeforeItsSteps) {
  auto d = std::make_shared<Discriminator>(options(0));
  const auto demos = gaussian(64, torch::ones({5}), no_z(64)), policy = gaussian(64, -torch::ones({5}), no_z(64));
  const auto expected = evaluate_discriminator(*d, demos, policy);
  DiscriminatorTrainer trainer(d, 1e-3);
  const auto reported = train_full_batch(trainer, demos, policy, 3);
  EXPECT_NEAR(reported.loss, expected.loss, 1e-6);
  EXPECT_DOUBLE_EQ(reported.demo_accuracy, expected.demo_accuracy);
  EXPECT_NE(evaluate_discriminator(*d, demos, policy).loss, expected.loss);
}

TEST_F(DiscriminatorTest, AMinibatchStepIsAFullBatchStepOnItsShareOfTheShuffle) {
  // Step 2 of 4 minibatches of 64 samples: rows 16..31 of randperm(64) from the same seed.
  const auto demos = gaussian(64, torch::ones({5}), no_z(64)), policy = gaussian(64, -torch::ones({5}), no_z(64));
  auto minibatched = std::make_shared<Discriminator>(options(0)), reference = std::make_shared<Discriminator>(options(0));
  torch::NoGradGuard no_grad;
  for (size_t i = 0; i < reference->parameters().size(); ++i)
    reference->parameters()[i].copy_(minibatched->parameters()[i]);
  auto generator = at::detail::createCPUGenerator(11), same = at::detail::createCPUGenerator(11);
  const auto rows = torch::randperm(64, same, torch::kLong);
  {
    torch::AutoGradMode grad(true);
    DiscriminatorTrainer a(minibatched, 1e-2), b(reference, 1e-2);
    a.train(demos, policy, 2, 4, generator);
    for (const auto& step_rows : {rows.slice(0, 0, 16), rows.slice(0, 16, 32)})
      train_full_batch(b, rows_of(demos, step_rows), rows_of(policy, step_rows), 1);
  }
  for (size_t i = 0; i < reference->parameters().size(); ++i)
    EXPECT_TRUE(torch::allclose(minibatched->parameters()[i], reference->parameters()[i], 1e-6, 1e-7)) << i;
}

// Demonstrations: z = +1 ↔ (x, a) around +1, z = -1 ↔ around -1. Policy: the same two
// clouds with the z's swapped. Without z both sides have the same distribution.
struct SwappedData {
  DiscriminatorData demos, policy;
};

SwappedData swapped(int64_t half) {
  const auto up = torch::ones({kObs + kAct}), down = -up;
  const auto z_up = torch::ones({half, 1}), z_down = -torch::ones({half, 1});
  const auto cat = [](const DiscriminatorData& a, const DiscriminatorData& b) {
    return DiscriminatorData{torch::cat({a.observations, b.observations}), torch::cat({a.actions, b.actions}),
                             torch::cat({a.z, b.z})};
  };
  return {cat(gaussian(half, up, z_up), gaussian(half, down, z_down)),
          cat(gaussian(half, down, z_up), gaussian(half, up, z_down))};
}

TEST_F(DiscriminatorTest, OnlyTheConditionalOneSeparatesSwappedConditions) {
  const auto train = swapped(512), test = swapped(1000);
  for (const int latent_dim : {1, 0}) {
    auto d = std::make_shared<Discriminator>(options(latent_dim));
    d->fit_normalization(train.demos.observations, train.demos.actions);
    DiscriminatorTrainer trainer(d, 1e-3);
    train_full_batch(trainer, train.demos, train.policy, 300);
    const auto s = evaluate_discriminator(*d, test.demos, test.policy);
    const double accuracy = (s.demo_accuracy + s.policy_accuracy) / 2;
    if (latent_dim == 1) {
      EXPECT_GT(accuracy, 0.9);
    } else {
      EXPECT_LT(accuracy, 0.6);
      EXPECT_GT(s.loss, 1.3);  // 2 log 2 = 1.386: no better than a coin
    }
  }
}

TEST_F(DiscriminatorTest, SeesOnlyItsStateSubsetAndClippedActions) {
  auto o = options(0);
  o.state_indices = {0, 2};
  o.action_low = {-1, -1};
  o.action_high = {1, 1};
  Discriminator d(o);
  const auto obs = torch::randn({6, kObs}), act = torch::randn({6, kAct}) * 3, z = no_z(6);
  auto other_obs = obs.clone();
  other_obs.select(1, 1).add_(5.0);
  torch::NoGradGuard no_grad;
  const auto logits = d.forward(obs, act, z);
  EXPECT_TRUE(torch::allclose(d.forward(other_obs, act, z), logits));
  EXPECT_TRUE(torch::allclose(d.forward(obs, act.clamp(-1, 1), z), logits));
  auto moved = obs.clone();
  moved.select(1, 2).add_(5.0);
  EXPECT_FALSE(torch::allclose(d.forward(moved, act, z), logits));
}

TEST_F(DiscriminatorTest, NormalisationIsStoredWithTheWeights) {
  Discriminator a(options(0)), b(options(0));
  const auto obs = torch::randn({50, kObs}) * 4 + 7, act = torch::randn({50, kAct});
  a.fit_normalization(obs, act);
  std::stringstream buffer;
  torch::serialize::OutputArchive out;
  a.save(out);
  out.save_to(buffer);
  torch::serialize::InputArchive in;
  in.load_from(buffer);
  b.load(in);
  torch::NoGradGuard no_grad;
  EXPECT_TRUE(torch::allclose(a.forward(obs, act, no_z(50)), b.forward(obs, act, no_z(50))));
}

}  // namespace
}  // namespace vaegail
