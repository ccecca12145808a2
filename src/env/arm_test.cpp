#include "env/arm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "env/registry.h"

namespace vaegail {
namespace {

// Published Jaco link lengths the model is built from (models/arm.xml).
constexpr double kShoulderHeight = 0.1535 + 0.122;
constexpr double kUpperArm = 0.41;
constexpr double kForearmToGrip = 0.2073 + 0.0743 + 0.0743 + 0.1687;

// The grip by hand: arm_1 turns about z, arm_2 and arm_3 bend about y, the others at 0.
std::array<double, 3> grip_by_hand(double q1, double q2, double q3) {
  const double r = kUpperArm * std::sin(q2) + kForearmToGrip * std::cos(q2 + q3);
  const double z = kShoulderHeight + kUpperArm * std::cos(q2) - kForearmToGrip * std::sin(q2 + q3);
  return {r * std::cos(q1), r * std::sin(q1), z};
}

std::vector<float> sway(int t) {
  std::vector<float> a(ArmEnv::kJoints);
  for (int i = 0; i < ArmEnv::kJoints; ++i) a[i] = 0.5f * std::sin(0.4 * t + i);
  return a;
}

TEST(Arm, HasNineDofsNineActuatorsAndPaperTiming) {
  ArmEnv env;
  EXPECT_EQ(env.model()->nq, 9);
  EXPECT_EQ(env.act_dim(), 9);
  EXPECT_EQ(env.obs_dim(), 21);
  EXPECT_DOUBLE_EQ(env.control_timestep(), 0.05);
  EXPECT_EQ(env.episode_length(), 50);
  EXPECT_DOUBLE_EQ(env.control_timestep() * env.episode_length(), 2.5);
  EXPECT_EQ(env.context_names(), (std::vector<std::string>{"target_x", "target_y", "target_z"}));
}

TEST(Arm, EveryEpisodeStartsFromTheHomePoseWithTheGripWhereTheLinkLengthsPutIt) {
  ArmEnv env;
  env.reset(1);
  const auto first = env.observation();
  env.reset(987654);
  EXPECT_EQ(env.observation(), first);  // the seed does not move the start
  const auto home = grip_by_hand(0, 0, 0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(first[18 + k], home[k], 1e-6);
  for (int j = 0; j < 18; ++j) EXPECT_EQ(first[j], 0.0f);
}

TEST(Arm, GripFeatureMatchesForwardKinematicsByHand) {
  ArmEnv env;
  env.reset(0);
  // Pose the arm directly (the test reaches into the simulator state on purpose).
  auto* d = const_cast<mjData*>(env.data());
  const double q1 = 0.7, q2 = 0.5, q3 = -0.9;
  d->qpos[0] = q1;
  d->qpos[1] = q2;
  d->qpos[2] = q3;
  mj_kinematics(env.model(), d);
  double f[4];
  env.features(f);
  const auto expected = grip_by_hand(q1, q2, q3);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], expected[k], 1e-9);
}

TEST(Arm, ObservationAndDistanceFollowTheSimulatorState) {
  ArmEnv env;
  env.set_context({0.5, 0.2, 0.3});
  env.reset(0);
  for (int t = 0; t < 10; ++t) env.step(sway(t).data());
  const auto obs = env.observation();
  const mjData* d = env.data();
  for (int j = 0; j < 9; ++j) {
    EXPECT_FLOAT_EQ(obs[j], static_cast<float>(d->qpos[j]));
    EXPECT_FLOAT_EQ(obs[9 + j], static_cast<float>(d->qvel[j]));
  }
  EXPECT_NE(obs[0], 0.0f);  // the actions moved it
  double f[4];
  env.features(f);
  const double dist = std::sqrt((obs[18] - 0.5) * (obs[18] - 0.5) + (obs[19] - 0.2) * (obs[19] - 0.2) +
                                (obs[20] - 0.3) * (obs[20] - 0.3));
  EXPECT_NEAR(f[3], dist, 1e-6);
  EXPECT_NEAR(env.target_distance(), dist, 1e-6);
}

TEST(Arm, RewardMatchesHandComputedValues) {
  EXPECT_NEAR(ArmEnv::task_reward(0.0), 1.0, 1e-12);
  EXPECT_NEAR(ArmEnv::task_reward(0.05), 0.5 * 0.95 + 0.5 * std::exp(-1.0), 1e-12);
  EXPECT_NEAR(ArmEnv::task_reward(0.25), 0.375 + 0.5 * std::exp(-25.0), 1e-12);
  EXPECT_NEAR(ArmEnv::task_reward(0.8), 0.1 + 0.5 * std::exp(-256.0), 1e-12);
  EXPECT_NEAR(ArmEnv::task_reward(1.5), 0.0, 1e-12);
}

TEST(Arm, RewardChargesEachCommandForItsDistanceFromTheAngleItWasGivenAt) {
  ArmOptions options;
  options.command_cost = 0.1;
  ArmEnv env(options);
  env.reset(0);
  // From the home pose (every angle 0); arm_1's 5 rad is clipped to its 2.967 rad range.
  const std::vector<float> command = {5.0f, -0.3f, 0.2f, 0, 0, 0, 0.4f, -0.4f, 0};
  const double first_jump = (2.967 * 2.967 + 0.09 + 0.04 + 0.16 + 0.16) / 9;
  const auto first = env.step(command.data());
  EXPECT_NEAR(env.command_jump(), first_jump, 1e-6);
  EXPECT_NEAR(first.reward, ArmEnv::task_reward(env.target_distance()) - 0.1 * first_jump, 1e-9);
  // The second step is charged against the angles the first one reached, not the home pose.
  std::vector<double> reached(env.data()->qpos, env.data()->qpos + ArmEnv::kJoints);
  const auto second = env.step(command.data());
  double sq = 0;
  for (int j = 0; j < ArmEnv::kJoints; ++j) sq += std::pow(env.data()->ctrl[j] - reached[j], 2);
  EXPECT_NEAR(env.command_jump(), sq / 9, 1e-9);
  EXPECT_LT(env.command_jump(), first_jump);
  EXPECT_NEAR(second.reward, ArmEnv::task_reward(env.target_distance()) - 0.1 * sq / 9, 1e-9);
}

TEST(Arm, RewardChargesThePoseForItsDistanceFromHome) {
  ArmOptions options;
  options.command_cost = 0;
  options.posture_cost = 0.2;
  ArmEnv env(options);
  env.reset(0);
  EXPECT_DOUBLE_EQ(env.posture_charge(), 0.0);  // the home pose is every angle 0
  const std::vector<float> command = {0.4f, 0.6f, 0.3f, -0.5f, 0.5f, 0.3f, 0.7f, -0.7f, -0.7f};
  StepOutcome out;
  for (int t = 0; t < 5; ++t) out = env.step(command.data());
  double sq = 0;
  for (int j = 0; j < ArmEnv::kJoints; ++j) sq += std::pow(env.data()->qpos[j], 2);
  EXPECT_GT(sq, 0.5);
  EXPECT_NEAR(env.posture_charge(), 0.2 * sq / 9, 1e-12);
  EXPECT_NEAR(out.reward, ArmEnv::task_reward(env.target_distance()) - 0.2 * sq / 9, 1e-9);
  // Off by default: the published experts' reward has no posture term.
  ArmEnv plain;
  plain.reset(0);
  plain.step(command.data());
  EXPECT_DOUBLE_EQ(plain.posture_charge(), 0.0);
}

TEST(Arm, ServosSettleOnTheCommandedAnglesWithinHalfASecond) {
  ArmEnv env;
  env.reset(0);
  // A pose in front of the base: every arm joint commanded away from home.
  const std::vector<float> command = {0.4f, 0.6f, 0.3f, -0.5f, 0.5f, 0.3f, 0.7f, -0.7f, -0.7f};
  std::vector<float> overshoot(9, 0.0f);
  for (int t = 0; t < 20; ++t) {
    env.step(command.data());
    const auto obs = env.observation();
    for (int j = 0; j < 9; ++j)
      overshoot[j] = std::max(overshoot[j], command[j] > 0 ? obs[j] - command[j] : command[j] - obs[j]);
    if (t == 9) {  // 0.5 s
      for (int j = 0; j < 9; ++j) EXPECT_NEAR(obs[j], command[j], 0.12) << "joint " << j;
    }
  }
  const auto obs = env.observation();
  for (int j = 0; j < 9; ++j) {
    EXPECT_NEAR(obs[j], command[j], 0.12) << "joint " << j;  // gravity sag only
    EXPECT_LT(std::abs(obs[9 + j]), 0.05) << "joint " << j;  // and at rest
    EXPECT_LT(overshoot[j], 0.1) << "joint " << j;           // about critically damped
  }
}

TEST(Arm, TargetsLieInTheWorkspaceAndWithinReach) {
  Rng rng(5);
  for (int i = 0; i < 200; ++i) {
    const auto t = ArmEnv::random_target(rng);
    double sq = 0;
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(t[k], ArmEnv::kTargetLow[k]);
      EXPECT_LE(t[k], ArmEnv::kTargetHigh[k]);
      const double from_shoulder = t[k] - (k == 2 ? kShoulderHeight : 0.0);
      sq += from_shoulder * from_shoulder;
    }
    EXPECT_LT(std::sqrt(sq), kUpperArm + kForearmToGrip);
    EXPECT_GT(std::sqrt(sq), kForearmToGrip - kUpperArm);
  }
}

TEST(Arm, TheTableTopStopsTheLinks) {
  ArmEnv env;
  env.reset(0);
  Rng rng(11);
  std::vector<float> a(ArmEnv::kJoints);
  double lowest_grip = 1.0, lowest_body = 1.0;
  for (int t = 0; t < 4 * env.episode_length(); ++t) {
    for (auto& u : a) u = static_cast<float>(rng.uniform(-1, 1));
    a[1] = 2.0f;  // drive the shoulder down towards the table
    a[2] = 1.0f;
    env.step(a.data());
    lowest_grip = std::min(lowest_grip, env.grip_position()[2]);
    // Every link's frame sits on its geom's axis, at least the geom's radius above a contact.
    for (int b = 1; b < env.model()->nbody; ++b) lowest_body = std::min(lowest_body, env.data()->xpos[3 * b + 2]);
  }
  EXPECT_LT(lowest_grip, 0.15);     // the hand got down there
  EXPECT_GT(lowest_body, -0.005);   // and no link passed through
}

TEST(Arm, IsABuiltInTaskWhoseContextSurvivesCloneAndWhoseSeedsReplay) {
  EnvRequest request;
  request.task = "arm";
  auto env = make_env(request);
  EXPECT_EQ(env->id(), "arm");
  env->set_context({0.3, -0.1, 0.2});
  auto copy = env->clone();
  EXPECT_EQ(copy->context(), env->context());
  env->reset(3);
  copy->reset(3);
  for (int t = 0; t < 50; ++t) {
    const auto a = sway(t);
    const auto x = env->step(a.data());
    const auto y = copy->step(a.data());
    EXPECT_EQ(x.reward, y.reward);
    EXPECT_EQ(x.truncated, t == 49);
  }
  EXPECT_EQ(env->observation(), copy->observation());
}

}  // namespace
}  // namespace vaegail
