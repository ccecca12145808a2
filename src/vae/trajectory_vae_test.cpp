#include "vae/trajectory_vae.h"

#include <gtest/gtest.h>

#include "vae/gaussian.h"
#include "vae/toy_trajectories.h"

namespace vaegail::vae {
namespace {

using testing::tiny_vae_config;

class TrajectoryVaeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::set_num_threads(1);
    torch::manual_seed(8);
  }
};

TEST_F(TrajectoryVaeTest, LossTermsAddUp) {
  auto c = tiny_vae_config();
  c.kl_weight = 0.25;
  TrajectoryVae vae(c);
  const auto [states, actions] = testing::toy_trajectories(3, 10, 4, 2, 1);
  vae->fit_normalization(states, actions);
  const auto loss = vae->loss(states, actions, {}, torch::randn({3, 2}));
  EXPECT_EQ(loss.per_trajectory.sizes(), torch::IntArrayRef({3}));
  EXPECT_NEAR(loss.total.item<double>(),
              loss.action_nll.item<double>() + loss.state_nll.item<double>() +
                  0.25 * loss.kl.item<double>(),
              1e-3);
  EXPECT_NEAR(loss.per_trajectory.mean().item<double>(), loss.total.item<double>(), 1e-4);
  EXPECT_GT(loss.kl.item<double>(), 0.0);
}

TEST_F(TrajectoryVaeTest, LossIsTheSumOfTheThreeDensities) {
  // Recompute the objective of one trajectory from the parts, with z fixed through the noise.
  TrajectoryVae vae(tiny_vae_config());
  const auto [states, actions] = testing::toy_trajectories(1, 6, 4, 2, 2);
  vae->fit_normalization(states, actions);
  const auto noise = torch::randn({1, 2});
  const auto loss = vae->loss(states, actions, {}, noise);
  const auto x = vae->normalize_states(states), a = vae->normalize_actions(actions);
  const auto q = vae->encoder()->forward(x);
  const auto z = q.mean + q.log_std.exp() * noise;
  double action_lp = 0, state_lp = 0;
  for (int t = 0; t < 6; ++t) {
    const auto xt = x.select(1, t), xn = x.select(1, t + 1);
    action_lp += vae->action_decoder()->log_prob(xt, z, a.select(1, t)).item<double>();
    state_lp += mixture_log_prob(xn, vae->state_decoder()->forward_reference(xt, xn, z))
                    .sum()
                    .item<double>();
  }
  EXPECT_NEAR(loss.action_nll.item<double>(), -action_lp, 1e-3);
  EXPECT_NEAR(loss.state_nll.item<double>(), -state_lp, 1e-3);
  // The decoders' part alone, at the same z.
  const auto nll = vae->decoder_nll(states, actions, z);
  EXPECT_NEAR(nll.action.item<double>(), -action_lp, 1e-3);
  EXPECT_NEAR(nll.state.item<double>(), -state_lp, 1e-3);
}

TEST_F(TrajectoryVaeTest, EncoderInputNoiseReachesOnlyTheEncoderAndOnlyInTraining) {
  auto c = tiny_vae_config();
  c.encoder_input_noise = 0.5;
  TrajectoryVae vae(c);
  const auto [states, actions] = testing::toy_trajectories(2, 6, 4, 2, 3);
  vae->fit_normalization(states, actions);
  const auto eps = torch::randn({2, 2});
  const auto x = vae->normalize_states(states), a = vae->normalize_actions(actions);

  torch::manual_seed(21);
  const auto noisy = vae->loss(states, actions, {}, eps);
  torch::manual_seed(21);
  const auto q = vae->encoder()->forward(x + 0.5 * torch::randn_like(x));
  const auto z = q.mean + q.log_std.exp() * eps;
  double action_lp = 0;
  for (int t = 0; t < 6; ++t)
    action_lp += vae->action_decoder()->log_prob(x.select(1, t), z, a.select(1, t)).sum().item<double>();
  EXPECT_NEAR(noisy.action_nll.item<double>(), -action_lp / 2, 1e-3);  // the decoder saw clean states
  EXPECT_NEAR(noisy.kl.item<double>(), kl_to_standard_normal(q.mean, q.log_std).mean().item<double>(), 1e-4);
  // The same draw passed in (as the trainer does, to slice one draw over ranks).
  torch::manual_seed(21);
  const auto given = vae->loss(states, actions, {}, eps, torch::randn_like(x));
  EXPECT_NEAR(given.kl.item<double>(), noisy.kl.item<double>(), 1e-6);

  vae->eval();
  const auto clean = vae->loss(states, actions, {}, eps);
  const auto q_clean = vae->encoder()->forward(x);
  EXPECT_NEAR(clean.kl.item<double>(), kl_to_standard_normal(q_clean.mean, q_clean.log_std).mean().item<double>(), 1e-4);
  EXPECT_GT(std::abs(clean.kl.item<double>() - noisy.kl.item<double>()), 1e-4);
}

TEST_F(TrajectoryVaeTest, TheEncoderReadsOnlyItsStateIndices) {
  auto c = tiny_vae_config();
  c.encoder_state_indices = {3, 1};
  TrajectoryVae vae(c);
  const auto [states, actions] = testing::toy_trajectories(2, 6, 4, 2, 4);
  vae->fit_normalization(states, actions);
  const auto q = vae->encode(states);
  auto other = states.clone();
  other.select(2, 0).add_(5.0);
  other.select(2, 2).mul_(-3.0);
  EXPECT_TRUE(torch::allclose(vae->encode(other).mean, q.mean));
  auto moved = states.clone();
  moved.select(2, 3).add_(1.0);
  EXPECT_FALSE(torch::allclose(vae->encode(moved).mean, q.mean));
  const auto x = vae->normalize_states(states);
  const auto direct = vae->encoder()->forward(torch::stack({x.select(2, 3), x.select(2, 1)}, 2));
  EXPECT_TRUE(torch::allclose(direct.mean, q.mean));
  EXPECT_TRUE(std::isfinite(vae->loss(states, actions).total.item<double>()));
}

TEST_F(TrajectoryVaeTest, ActionsRelativeToTheStateAreModelledAsTheirDifference) {
  auto c = tiny_vae_config();
  c.action_relative_to_state = {2, 0};
  TrajectoryVae vae(c);
  const auto [states, actions] = testing::toy_trajectories(3, 6, 4, 2, 5);
  vae->fit_normalization(states, actions);
  const auto x_t = states.narrow(1, 0, 6);
  const auto difference = actions - torch::stack({x_t.select(2, 2), x_t.select(2, 0)}, 2);
  EXPECT_TRUE(torch::allclose(vae->modelled_actions(states, actions), difference));
  // The normalisation is that of the difference ...
  const auto a = vae->normalize_actions(difference);
  EXPECT_LT(a.reshape({-1, 2}).mean(0).abs().max().item<double>(), 1e-4);
  // ... the likelihood too ...
  const auto noise = torch::randn({3, 2});
  const auto loss = vae->loss(states, actions, {}, noise);
  const auto x = vae->normalize_states(states);
  const auto q = vae->encoder()->forward(x);
  const auto z = (q.mean + q.log_std.exp() * noise).unsqueeze(1).expand({3, 6, 2});
  const auto action_lp = vae->action_decoder()->log_prob(x.narrow(1, 0, 6), z, a).sum(1).mean();
  EXPECT_NEAR(loss.action_nll.item<double>(), -action_lp.item<double>(), 1e-3);
  // ... and the policy's action is the decoded difference plus the state components.
  const auto s0 = states.select(1, 0), z0 = torch::zeros({3, 2});
  auto buffers = vae->named_buffers();
  const auto decoded = vae->action_decoder()->mean(vae->normalize_states(s0), z0) *
                           buffers["action_std"] + buffers["action_mean"];
  EXPECT_TRUE(torch::allclose(vae->action_mean(s0, z0) - decoded,
                              torch::stack({s0.select(1, 2), s0.select(1, 0)}, 1), 1e-5, 1e-5));
}

TEST_F(TrajectoryVaeTest, MaskedLossEqualsLossOfTheTruncatedTrajectory) {
  TrajectoryVae vae(tiny_vae_config());
  const auto [states, actions] = testing::toy_trajectories(2, 8, 4, 2, 3);
  vae->fit_normalization(states, actions);
  const auto noise = torch::randn({2, 2});
  auto mask = torch::ones({2, 8}, torch::kBool);
  mask.index_put_({0, torch::indexing::Slice(5)}, false);  // trajectory 0: 5 steps
  auto padded_states = states.clone(), padded_actions = actions.clone();
  padded_states.index_put_({0, torch::indexing::Slice(6)}, NAN);
  padded_actions.index_put_({0, torch::indexing::Slice(5)}, NAN);
  const auto both = vae->loss(padded_states, padded_actions, mask, noise);
  const auto short0 = vae->loss(states.narrow(0, 0, 1).narrow(1, 0, 6),
                                actions.narrow(0, 0, 1).narrow(1, 0, 5), {}, noise.narrow(0, 0, 1));
  const auto full1 = vae->loss(states.narrow(0, 1, 1), actions.narrow(0, 1, 1), {}, noise.narrow(0, 1, 1));
  EXPECT_NEAR(both.per_trajectory[0].item<double>(), short0.total.item<double>(), 1e-3);
  EXPECT_NEAR(both.per_trajectory[1].item<double>(), full1.total.item<double>(), 1e-3);
  // NaN padding leaves no trace in the gradients either.
  both.total.backward();
  for (const auto& p : vae->parameters())
    EXPECT_TRUE(torch::isfinite(p.grad()).all().item<bool>());
}

TEST_F(TrajectoryVaeTest, NormalisationIsStoredInTheModule) {
  TrajectoryVae vae(tiny_vae_config());
  const auto [states, actions] = testing::toy_trajectories(4, 5, 4, 2, 4);
  vae->fit_normalization(states, actions);
  const auto x = vae->normalize_states(states.reshape({-1, 4}));
  EXPECT_LT(x.mean(0).abs().max().item<double>(), 1e-4);
  EXPECT_NEAR(x.std(0, /*unbiased=*/false).mean().item<double>(), 1.0, 1e-4);
  const auto buffers = vae->named_buffers();
  ASSERT_TRUE(buffers.contains("state_mean") && buffers.contains("action_std"));
  std::stringstream stream;
  torch::save(vae, stream);
  TrajectoryVae copy(tiny_vae_config());
  torch::load(copy, stream);
  EXPECT_TRUE(torch::equal(copy->named_buffers()["state_std"], buffers["state_std"]));
  EXPECT_TRUE(torch::allclose(copy->action_mean(states.select(1, 0), torch::zeros({4, 2})),
                              vae->action_mean(states.select(1, 0), torch::zeros({4, 2}))));
}

TEST_F(TrajectoryVaeTest, ThePolicysInputStdIsFlooredAndNothingElseIs) {
  TrajectoryVae vae(tiny_vae_config());
  // Component 0 of the state nearly constant (std 1e-3), the others not.
  auto [states, actions] = testing::toy_trajectories(4, 5, 4, 2, 6);
  states.select(2, 0).mul_(1e-3);
  vae->fit_normalization(states, actions);
  const auto z = torch::randn({4, 5, 2});
  const auto x = vae->normalize_states(states.narrow(1, 0, 5));
  const auto plain = vae->action_mean(states.narrow(1, 0, 5), z);
  const auto eps = torch::randn({4, 2});
  const auto loss = vae->loss(states, actions, {}, eps);
  vae->set_policy_state_std_floor(0.05);
  // The policy sees component 0 divided by 0.05 instead of its own std: scaled by std / 0.05.
  const auto std0 = vae->named_buffers()["state_std"][0].item<double>();
  ASSERT_LT(std0, 0.05);
  auto expected = x.clone();
  expected.select(2, 0).mul_(std0 / 0.05);
  EXPECT_TRUE(torch::allclose(vae->policy_input(x), expected));
  const auto floored = vae->action_mean(states.narrow(1, 0, 5), z);
  EXPECT_FALSE(torch::allclose(floored, plain));
  EXPECT_TRUE(torch::allclose(floored, vae->action_decoder()->mean(expected, z) *
                                           vae->named_buffers()["action_std"] + vae->named_buffers()["action_mean"]));
  // The encoder and the state decoder are untouched: the loss changes in its action term only.
  const auto after = vae->loss(states, actions, {}, eps);
  EXPECT_FLOAT_EQ(after.state_nll.item<float>(), loss.state_nll.item<float>());
  EXPECT_FLOAT_EQ(after.kl.item<float>(), loss.kl.item<float>());
  EXPECT_NE(after.action_nll.item<float>(), loss.action_nll.item<float>());
  EXPECT_EQ(VaeConfig::from_json(vae->config().to_json()).policy_state_std_floor, 0.05);
}

TEST_F(TrajectoryVaeTest, OverfitsTwoTrajectoriesAndSeparatesTheirEmbeddings) {
  TrajectoryVae vae(tiny_vae_config());
  auto [states, actions] = testing::toy_trajectories(2, 20, 4, 2, 9);
  vae->fit_normalization(states, actions);
  torch::optim::Adam opt(vae->parameters(), torch::optim::AdamOptions(1e-2));
  const double initial = vae->loss(states, actions).total.item<double>();
  double final_loss = 0;
  for (int step = 0; step < 300; ++step) {
    opt.zero_grad();
    auto loss = vae->loss(states, actions);
    loss.total.backward();
    opt.step();
    final_loss = loss.total.item<double>();
  }
  ASSERT_GT(initial, 0.0);
  EXPECT_LT(final_loss, 0.2 * initial) << "initial " << initial;
  // Each trajectory's posterior mean lies several posterior stds away from the other's.
  torch::NoGradGuard no_grad;
  const auto q = vae->encode(states);
  const auto gap = (q.mean[0] - q.mean[1]).abs();
  const auto spread = torch::max(q.log_std[0].exp(), q.log_std[1].exp());
  EXPECT_GT((gap / spread).max().item<double>(), 3.0)
      << "means " << q.mean << " stds " << q.log_std.exp();
}

TEST_F(TrajectoryVaeTest, RolloutHelpersWorkInRawUnits) {
  TrajectoryVae vae(tiny_vae_config());
  const auto [states, actions] = testing::toy_trajectories(3, 4, 4, 2, 10);
  vae->fit_normalization(states, actions);
  const auto z = torch::zeros({3, 2});
  EXPECT_EQ(vae->action_mean(states.select(1, 0), z).sizes(), torch::IntArrayRef({3, 2}));
  auto gen = at::detail::createCPUGenerator(1);
  const auto next = vae->sample_next_state(states.select(1, 0), z, gen);
  EXPECT_EQ(next.sizes(), torch::IntArrayRef({3, 4}));
  EXPECT_TRUE(torch::isfinite(next).all().item<bool>());
}

}  // namespace
}  // namespace vaegail::vae
