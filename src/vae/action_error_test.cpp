#include "vae/action_error.h"

#include <gtest/gtest.h>

#include "vae/toy_trajectories.h"

namespace vaegail::vae {
namespace {

TrajectoryVae tiny_vae() { return TrajectoryVae(testing::tiny_vae_config(4, 2)); }

// Demonstrations whose actions are the decoder's own mean under z, shifted by (first, later).
TrajectoryDataset shifted_demos(TrajectoryVae& vae, const torch::Tensor& z, float first, float later) {
  torch::NoGradGuard no_grad;
  auto [states, actions] = testing::toy_trajectories(4, 5, 4, 2, 1);
  vae->fit_normalization(states, actions);
  const auto z_steps = z.unsqueeze(1).expand({4, 5, 2});
  auto shift = torch::full({4, 5, 2}, later);
  shift.select(1, 0).fill_(first);
  return {states, vae->action_mean(states.narrow(1, 0, 5), z_steps) + shift, {}};
}

TEST(ActionErrorTest, IsTheRmsOfTheActionErrorAtTheFirstAndTheLaterSteps) {
  torch::manual_seed(3);
  auto vae = tiny_vae();
  const auto z = torch::randn({4, 2});
  const auto data = shifted_demos(vae, z, 0.5f, -0.25f);
  const auto e = teacher_forced_action_error(vae, data, z);
  EXPECT_NEAR(e.first_step, 0.5, 1e-5);
  EXPECT_NEAR(e.later_steps, 0.25, 1e-5);
  EXPECT_THROW(teacher_forced_action_error(vae, data, torch::zeros({3, 2})), std::invalid_argument);
}

TEST(ActionErrorTest, OnlyTheOwnZReproducesADecoderThatReadsZ) {
  torch::manual_seed(4);
  auto vae = tiny_vae();
  const auto z = 3 * torch::randn({4, 2});
  auto data = shifted_demos(vae, z, 0.0f, 0.0f);
  const auto rows = action_error_by_z_source(vae, data, z);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].z_source, "own");
  EXPECT_NEAR(rows[0].error.later_steps, 0.0, 1e-5);
  EXPECT_GT(rows[1].error.later_steps, 1e-3);
  EXPECT_GT(rows[2].error.later_steps, 1e-3);
  // Padding (even NaN) is not counted.
  data.mask = torch::ones({4, 5}, torch::kBool);
  data.mask.index_put_({0, torch::indexing::Slice(3)}, false);
  data.actions.index_put_({0, torch::indexing::Slice(3)}, NAN);
  EXPECT_NEAR(teacher_forced_action_error(vae, data, z).later_steps, 0.0, 1e-5);
}

}  // namespace
}  // namespace vaegail::vae
