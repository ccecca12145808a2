#include "vae/latent_refinement.h"

#include <gtest/gtest.h>

#include "vae/toy_trajectories.h"

namespace vaegail::vae {
namespace {

struct Fixture {
  TrajectoryVae vae{testing::tiny_vae_config(4, 2)};
  TrajectoryDataset data;
  torch::Tensor start;
};

Fixture fixture() {
  torch::manual_seed(5);
  Fixture f;
  auto [states, actions] = testing::toy_trajectories(3, 6, 4, 2, 2);
  f.vae->fit_normalization(states, actions);
  f.data = {states, actions, {}};
  f.start = torch::randn({3, 2});
  return f;
}

TEST(LatentRefinementTest, ObjectiveIsTheDecodersNllPlusTheGaussianPrior) {
  auto f = fixture();
  torch::NoGradGuard no_grad;
  const auto nll = f.vae->decoder_nll(f.data.states, f.data.actions, f.start);
  const auto expected = nll.action + nll.state + 0.5 * f.start.square().sum(-1);
  EXPECT_TRUE(torch::allclose(latent_objective(f.vae, f.data, f.start), expected));
}

TEST(LatentRefinementTest, LowersEveryDemonstrationsObjective) {
  auto f = fixture();
  const auto before = latent_objective(f.vae, f.data, f.start);
  const auto z = refine_latents(f.vae, f.data, f.start, {50, 0.05, 64});
  const auto after = latent_objective(f.vae, f.data, z);
  for (int64_t i = 0; i < 3; ++i) EXPECT_LT(after[i].item<double>(), before[i].item<double>() - 1e-3) << i;
  EXPECT_TRUE(torch::equal(refine_latents(f.vae, f.data, f.start, {0, 0.05, 64}), f.start));
}

TEST(LatentRefinementTest, ReportIsTheMeanObjectiveBeforeAndAfter) {
  auto f = fixture();
  const auto r = refine_with_report(f.vae, f.data, f.start, {10, 0.05, 64});
  EXPECT_TRUE(torch::equal(r.z, refine_latents(f.vae, f.data, f.start, {10, 0.05, 64})));
  EXPECT_NEAR(r.objective_before, latent_objective(f.vae, f.data, f.start).mean().item<double>(), 1e-6);
  EXPECT_NEAR(r.objective_after, latent_objective(f.vae, f.data, r.z).mean().item<double>(), 1e-6);
  EXPECT_LT(r.objective_after, r.objective_before);
  EXPECT_NE(r.description.find("10 Adam steps"), std::string::npos) << r.description;
}

TEST(LatentRefinementTest, EachDemonstrationMovesOnItsOwn) {
  auto f = fixture();
  const auto together = refine_latents(f.vae, f.data, f.start, {20, 0.05, 64});
  const auto one_by_one = refine_latents(f.vae, f.data, f.start, {20, 0.05, 1});
  EXPECT_TRUE(torch::allclose(together, one_by_one, 1e-4, 1e-5));
  EXPECT_FALSE(torch::allclose(together, f.start));
}

TEST(LatentRefinementTest, RejectsAStartOfTheWrongShape) {
  auto f = fixture();
  EXPECT_THROW(refine_latents(f.vae, f.data, torch::zeros({2, 2})), std::invalid_argument);
  EXPECT_THROW(refine_latents(f.vae, f.data, f.start, {-1, 0.05, 64}), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail::vae
