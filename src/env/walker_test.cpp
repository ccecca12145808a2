#include "env/walker.h"

#include "env/embedded_models.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vaegail {
namespace {

// Centre of mass of all bodies but the world, computed from MuJoCo's body frames.
double com_x(const MujocoEnv& env) {
  const mjModel* m = env.model();
  double mx = 0, mass = 0;
  for (int b = 1; b < m->nbody; ++b) {
    mx += m->body_mass[b] * env.data()->xipos[3 * b];
    mass += m->body_mass[b];
  }
  return mx / mass;
}

std::vector<float> wobble(int t) {
  std::vector<float> a(6);
  for (int i = 0; i < 6; ++i) a[i] = 0.6f * std::sin(0.3 * t + i);
  return a;
}

TEST(Walker, HasNineDofsSixActuatorsAndPaperTiming) {
  WalkerEnv env;
  EXPECT_EQ(env.model()->nq, 9);
  EXPECT_EQ(env.model()->nv, 9);
  EXPECT_EQ(env.act_dim(), 6);
  EXPECT_EQ(env.obs_dim(), 18);
  EXPECT_DOUBLE_EQ(env.control_timestep(), 0.025);
  EXPECT_EQ(env.episode_length(), 400);
  EXPECT_DOUBLE_EQ(env.control_timestep() * env.episode_length(), 10.0);
}

TEST(Walker, ObservationLayoutMatchesSimulatorState) {
  WalkerEnv env;
  env.reset(3);
  for (int t = 0; t < 20; ++t) env.step(wobble(t).data());
  const auto obs = env.observation();
  const mjData* d = env.data();
  const int torso = mj_name2id(env.model(), mjOBJ_BODY, "torso");
  EXPECT_FLOAT_EQ(obs[0], static_cast<float>(d->xpos[3 * torso + 2]));
  EXPECT_FLOAT_EQ(obs[1], static_cast<float>(std::sin(d->qpos[2])));
  EXPECT_FLOAT_EQ(obs[2], static_cast<float>(std::cos(d->qpos[2])));
  const char* joints[] = {"right_hip", "right_knee", "right_ankle", "left_hip", "left_knee", "left_ankle"};
  for (int j = 0; j < 6; ++j) {
    const int id = mj_name2id(env.model(), mjOBJ_JOINT, joints[j]);
    EXPECT_EQ(env.observation_spec().names[3 + j], std::string(joints[j]) + "_angle");
    EXPECT_FLOAT_EQ(obs[3 + j], static_cast<float>(d->qpos[env.model()->jnt_qposadr[id]]));
    EXPECT_FLOAT_EQ(obs[12 + j], static_cast<float>(d->qvel[env.model()->jnt_dofadr[id]]));
  }
  const int rootx = mj_name2id(env.model(), mjOBJ_JOINT, "rootx");
  EXPECT_FLOAT_EQ(obs[9], static_cast<float>(d->qvel[env.model()->jnt_dofadr[rootx]]));
}

TEST(Walker, SpeedFeatureMatchesFiniteDifferenceOfCentreOfMass) {
  // Over a control step the finite difference of the centre of mass is the mean speed, which
  // the mean of the speeds at the step's ends matches to O(dt^2): run the walker's body at a
  // tenth of its timestep so that the two must agree closely even through foot impacts.
  std::string xml = embedded_model("walker.xml");
  const std::string from = "timestep=\"0.0025\"";
  ASSERT_NE(xml.find(from), std::string::npos);
  xml.replace(xml.find(from), from.size(), "timestep=\"0.00025\"");
  WalkerOptions o;
  o.terminate_on_fall = false;
  o.episode_length = 100000;
  WalkerEnv walker(MujocoModel::from_xml("walker_fine.xml", xml), o);
  walker.reset(11);
  const double dt = walker.control_timestep();
  double f[3];
  walker.features(f);
  double prev_x = com_x(walker), prev_v = f[0], worst = 0, total = 0, moved = 0;
  for (int k = 0; k < 4000; ++k) {
    walker.step(wobble(k / 100).data());
    walker.features(f);
    const double x = com_x(walker);
    const double error = std::abs((x - prev_x) / dt - 0.5 * (prev_v + f[0]));
    worst = std::max(worst, error);
    total += error;
    moved = std::max(moved, std::abs(f[0]));
    prev_x = x;
    prev_v = f[0];
  }
  // Impacts make single steps err most; the torso's speed, say, would be off by ~0.5 m/s.
  EXPECT_GT(moved, 0.5);
  EXPECT_LT(worst, 0.02);
  EXPECT_LT(total / 4000, 0.002);
}

TEST(Walker, HeightAndFallenFeaturesFollowTheTorso) {
  WalkerEnv env;
  env.reset(5);
  double f[3];
  env.features(f);
  EXPECT_NEAR(f[1], 1.3, 0.01);
  EXPECT_EQ(f[2], 0.0);
  const std::vector<float> limp(6, 0.f);
  StepOutcome out;
  int steps = 0;
  do {
    out = env.step(limp.data());
    ++steps;
  } while (!out.done());
  env.features(f);
  // A limp walker collapses long before the time limit, and the step that ends it is a fall.
  EXPECT_TRUE(out.terminated);
  EXPECT_LT(steps, 400);
  EXPECT_EQ(f[2], 1.0);
  EXPECT_TRUE(f[1] < WalkerEnv::kFallHeight || std::cos(env.torso_pitch()) < WalkerEnv::kFallCosPitch);
}

TEST(Walker, RewardMatchesHandComputedValues) {
  const float zero[6] = {0, 0, 0, 0, 0, 0};
  EXPECT_DOUBLE_EQ(WalkerEnv::task_reward(1.0, 1.0, 1.3, 0.0, zero, 6), 1.0);
  // 0.5 m/s too fast for a 1 m/s target: linear term 1 - 0.5/1, sharp term exp(-0.5).
  EXPECT_NEAR(WalkerEnv::task_reward(1.5, 1.0, 1.3, 0.0, zero, 6),
              0.2 + 0.8 * (0.6 * 0.5 + 0.4 * std::exp(-0.5)), 1e-12);
  // Standing still with a 3 m/s target pays the alive weight only; 1.5 m/s pays half the linear term.
  EXPECT_NEAR(WalkerEnv::task_reward(0.0, 3.0, 1.3, 0.0, zero, 6), 0.2 + 0.8 * 0.4 * std::exp(-18.0), 1e-12);
  EXPECT_NEAR(WalkerEnv::task_reward(1.5, 3.0, 1.3, 0.0, zero, 6),
              0.2 + 0.8 * (0.6 * 0.5 + 0.4 * std::exp(-4.5)), 1e-12);
  EXPECT_NEAR(WalkerEnv::task_reward(3.0, 3.0, 1.0, 0.0, zero, 6), 0.5, 1e-12);
  EXPECT_NEAR(WalkerEnv::task_reward(0.0, 0.0, 1.3, M_PI / 2, zero, 6), 0.5, 1e-12);
  const float full[6] = {1, -1, 1, -1, 1, 5};  // clipped to 1
  EXPECT_NEAR(WalkerEnv::task_reward(0.0, 0.0, 1.3, 0.0, full, 6), 0.95, 1e-12);
  // Closer to the target speed always pays more, from either side.
  EXPECT_GT(WalkerEnv::task_reward(2.8, 3.0, 1.3, 0, zero, 6), WalkerEnv::task_reward(2.0, 3.0, 1.3, 0, zero, 6));
  EXPECT_GT(WalkerEnv::task_reward(-0.8, -1.0, 1.3, 0, zero, 6), WalkerEnv::task_reward(0.0, -1.0, 1.3, 0, zero, 6));
}

TEST(Walker, PostureCostChargesTheMeanSquaredJointAngle) {
  WalkerOptions options;
  options.terminate_on_fall = false;
  options.posture_cost = 0.5;
  WalkerEnv env(options);
  env.set_context({1.0});
  env.reset(3);
  StepOutcome out;
  for (int t = 0; t < 8; ++t) out = env.step(wobble(t).data());
  const auto obs = env.observation();
  double sq = 0;
  for (int j = 3; j < 9; ++j) sq += double(obs[j]) * obs[j];  // the six joint angles
  EXPECT_GT(sq, 0.01);
  EXPECT_NEAR(env.posture_charge(), 0.5 * sq / 6, 1e-6);
  const auto action = wobble(7);
  EXPECT_NEAR(out.reward, WalkerEnv::task_reward(env.com_speed(), 1.0, env.torso_height(), env.torso_pitch(),
                                                 action.data(), 6) - 0.5 * sq / 6, 1e-6);
  // Off by default: the published experts' reward has no posture term.
  WalkerEnv plain;
  plain.reset(3);
  for (int t = 0; t < 8; ++t) plain.step(wobble(t).data());
  EXPECT_DOUBLE_EQ(plain.posture_charge(), 0.0);
}

TEST(Walker, SameSeedSameTrajectoryOtherSeedOtherStart) {
  WalkerEnv a, b;
  a.reset(21);
  b.reset(21);
  for (int t = 0; t < 50; ++t) {
    a.step(wobble(t).data());
    b.step(wobble(t).data());
  }
  EXPECT_EQ(a.observation(), b.observation());
  a.reset(21);
  b.reset(22);
  EXPECT_NE(a.observation(), b.observation());
}

TEST(Walker, TimeLimitTruncatesAtEpisodeLength) {
  WalkerOptions o;
  o.terminate_on_fall = false;
  o.episode_length = 30;
  WalkerEnv env(o);
  env.reset(0);
  for (int t = 1; t <= 30; ++t) {
    const StepOutcome out = env.step(wobble(t).data());
    EXPECT_FALSE(out.terminated);
    EXPECT_EQ(out.truncated, t == 30);
  }
}

TEST(Walker, ContextIsTheTargetSpeedAndSurvivesClone) {
  WalkerEnv env;
  EXPECT_EQ(env.context_names(), std::vector<std::string>{"target_speed"});
  env.set_context({3.0});
  EXPECT_THROW(env.set_context({1.0, 2.0}), std::invalid_argument);
  auto copy = env.clone();
  EXPECT_EQ(copy->context(), std::vector<double>{3.0});
}

TEST(Walker, ActionsAreClippedToTheControlRange) {
  WalkerEnv a, b;
  a.reset(4);
  b.reset(4);
  const std::vector<float> big(6, 7.f), one(6, 1.f);
  for (int t = 0; t < 10; ++t) {
    a.step(big.data());
    b.step(one.data());
  }
  EXPECT_EQ(a.observation(), b.observation());
}

}  // namespace
}  // namespace vaegail
