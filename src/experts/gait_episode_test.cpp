// The gait controller on the humanoid, whole episodes through the environment's physics-step
// hook: the walk stands, walks at the commanded speed and heading, and survives pushes.
#include "experts/gait_episode.h"
#include "experts/gait_eval.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

namespace vaegail {
namespace {

// The default walk from reset seed `seed`, with `pushes` random pushes.
GaitEpisodeResult default_walk(HumanoidEnv& env, std::uint64_t seed, int pushes) {
  GaitEpisodeOptions o;
  o.seed = seed;
  o.pushes = pushes;  // 200 N for 0.1 s each, at a time in [2, 8] s and a direction drawn from the seed
  return run_gait_episode(env, GaitParameters{}, o);
}

TEST(GaitEpisode, TheDefaultWalkStaysUpTenSecondsFromPerturbedStartsAboveOneMetrePerSecond) {
  HumanoidEnv env;
  for (std::uint64_t seed : {11, 12}) {
    const GaitEpisodeResult r = default_walk(env, seed, 0);
    EXPECT_FALSE(r.fallen) << seed;
    EXPECT_EQ(r.control_steps, env.episode_length());
    EXPECT_NEAR(r.time_up, 10.02, 1e-9);
    EXPECT_GT(r.speed, 1.0);
    EXPECT_GT(r.distance, 10.0);
    EXPECT_LT(std::abs(r.lateral_drift), 0.5);
    EXPECT_LT(r.heading_error, 0.1);
    EXPECT_GT(r.step_length, 0.35);
    EXPECT_NEAR(r.cadence, 60.0 * r.steps / r.time_up, 0.1 * r.cadence);
    EXPECT_NEAR(r.pelvis_height, r.style[kRootHeight], 1e-12);
    EXPECT_NEAR(r.signature[0], 1.2, 0.2);  // forward_speed over every step, the start included
  }
}

TEST(GaitEpisode, TheWalkSurvivesA200NewtonPushOnThePelvis) {
  HumanoidEnv env;
  for (std::uint64_t seed : {21, 22}) {
    const GaitEpisodeResult calm = default_walk(env, seed, 0), pushed = default_walk(env, seed, 1);
    EXPECT_FALSE(pushed.fallen) << seed;
    EXPECT_GT(std::abs(pushed.distance - calm.distance) + std::abs(pushed.lateral_drift - calm.lateral_drift), 0.02);
  }
}

TEST(GaitEpisode, TheCommandsSetTheSpeedAndTheHeading) {
  HumanoidEnv env;
  const GaitEpisodeResult slow = run_gait_episode(env, gait_parameters_from_json({{"speed", 0.8}}, "slow"), {});
  EXPECT_FALSE(slow.fallen);
  EXPECT_NEAR(slow.speed, 0.8, 0.15);
  const GaitEpisodeResult turned = run_gait_episode(env, gait_parameters_from_json({{"heading", 0.4}}, "turned"), {});
  EXPECT_FALSE(turned.fallen);
  EXPECT_LT(turned.final_heading_error, 0.1);
  EXPECT_NEAR(env.heading(), 0.4, 0.1);
  EXPECT_GT(turned.distance, 8.0);  // along the new heading
}

TEST(GaitEval, AStyleIsWalkedFromEachStartWithAndWithoutPushesAndItsMeansReported) {
  GaitEvalOptions o;
  o.episodes = 2;
  o.replay = true;
  int done = 0;
  const GaitStyleEvaluation e = evaluate_gait_style("walk", GaitParameters{}, o, [&] { ++done; });
  EXPECT_EQ(done, 2);
  EXPECT_EQ(e.falls, 0);
  EXPECT_EQ(e.pushed_falls, 0);
  EXPECT_GT(e.speed, 1.0);
  EXPECT_GT(e.cadence, 100.0);
  EXPECT_GT(e.control_steps_per_s, 0.0);
  // Held, the mean actions drift off within the episode (the prototype: 32-39 control steps).
  EXPECT_GT(e.replay_min, 5);
  EXPECT_LT(e.replay_max, 200);
  const auto row = gait_evaluation_row(e);
  EXPECT_EQ(row.front().first, "episodes");
  EXPECT_EQ(row.back().first, "signature_arm_swing");
  GaitStyleEvaluation measured = e;
  measured.raw_control_steps_per_s = 2000.0;
  const std::string table = format_gait_evaluations({e, measured});
  EXPECT_NE(table.find("walk                2/2      2/2"), std::string::npos) << table;
  EXPECT_EQ(table.find("ratio"), table.rfind("ratio"));  // only the style whose raw figure was measured
  EXPECT_NE(table.find(fmt::format("ratio {:.2f}", e.control_steps_per_s / 2000.0)), std::string::npos) << table;
}

}  // namespace
}  // namespace vaegail
