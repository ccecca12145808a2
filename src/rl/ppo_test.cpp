#include "rl/ppo.h"

#include <gtest/gtest.h>

#include "rl/test_support.h"

namespace vaegail {
namespace {

TEST(Ppo, SolvesThePointMassTask) { expect_solves_point_mass<Ppo>(PpoOptions{}); }

TEST(Ppo, TargetKlStopsTheUpdateEarly) {
  PointMassTask task(3);
  PpoOptions options;
  options.learning_rate = 1e-2;
  options.target_kl = 1e-4;
  Ppo ppo(task.agent().policy_ptr(), task.agent().critic_ptr(), options);
  PpoStats stats;
  task.train(1, [&](const UpdateBatch& batch) { stats = ppo.update(batch); });
  EXPECT_TRUE(stats.stopped_early);
  EXPECT_GT(stats.minibatch_steps, 0);
  EXPECT_LT(stats.minibatch_steps, options.epochs * options.minibatches);
  // The stop is read at an epoch's end, never inside one.
  EXPECT_EQ(stats.minibatch_steps % options.minibatches, 0);
}

}  // namespace
}  // namespace vaegail
