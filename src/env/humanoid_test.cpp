#include "env/humanoid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "env/registry.h"

namespace vaegail {
namespace {

// The 56 hinges of the CMU skeleton as the paper's body has them, side by side with their gears.
std::vector<std::string> expected_hinges() {
  std::vector<std::string> names;
  auto add = [&](const std::string& bone, const std::vector<std::string>& axes) {
    for (const auto& a : axes) names.push_back(bone + a);
  };
  for (const char* s : {"l", "r"}) {
    const std::string side = s;
    add(side + "femur", {"rz", "ry", "rx"});
    add(side + "tibia", {"rx"});
    add(side + "foot", {"rz", "rx"});
    add(side + "toes", {"rx"});
  }
  for (const char* bone : {"lowerback", "upperback", "thorax", "lowerneck", "upperneck", "head"})
    add(bone, {"rz", "ry", "rx"});
  for (const char* s : {"l", "r"}) {
    const std::string side = s;
    add(side + "clavicle", {"rz", "ry"});
    add(side + "humerus", {"rz", "ry", "rx"});
    add(side + "radius", {"rx"});
    add(side + "wrist", {"ry"});
    add(side + "hand", {"rz", "rx"});
    add(side + "fingers", {"rx"});
    add(side + "thumb", {"rz", "rx"});
  }
  return names;
}

double expected_gear(const std::string& joint) {
  auto has = [&](const char* part) { return joint.find(part) != std::string::npos; };
  if (has("femurrx")) return 120;
  if (has("tibia")) return 80;
  if (has("femur") || has("humerus") || has("radius") || has("back") || has("thorax")) return 40;
  return 20;
}

std::vector<float> hinge_wobble(int t) {
  std::vector<float> a(HumanoidEnv::kHinges);
  for (int i = 0; i < HumanoidEnv::kHinges; ++i) a[i] = 0.3f * std::sin(0.2 * t + i);
  return a;
}

// Holds the rest pose: stiffness in gear units per radian plus the gravity and Coriolis torques
// MuJoCo reports for the tree hanging from the root (qfrc_bias of the last physics step), which
// carry the upper body and the arms. The ankles balance the whole body over the feet, so they
// need twenty times the others' stiffness (gravity alone tips the body about them at ~570 N m/rad).
std::vector<float> pd_hold(const HumanoidEnv& env) {
  const mjModel* m = env.model();
  const mjData* d = env.data();
  std::vector<float> u(m->nu);
  for (int a = 0; a < m->nu; ++a) {
    const int joint = m->actuator_trnid[2 * a];
    const double gear = m->actuator_gear[6 * a];
    const bool ankle = std::string(mj_id2name(m, mjOBJ_JOINT, joint)).find("foot") != std::string::npos;
    const double stiffness = (ankle ? 60.0 : 3.0) * gear;
    const double torque = d->qfrc_bias[m->jnt_dofadr[joint]] - stiffness * d->qpos[m->jnt_qposadr[joint]];
    u[a] = static_cast<float>(std::clamp(torque / gear, -1.0, 1.0));
  }
  return u;
}

TEST(Humanoid, HasTheCmuSkeletonsFiftySixHingesAndMotorsByName) {
  HumanoidEnv env;
  const mjModel* m = env.model();
  EXPECT_EQ(m->nq, 63);
  EXPECT_EQ(m->nv, 62);
  EXPECT_EQ(m->nu, 56);
  EXPECT_EQ(m->nbody, 32);  // the world and the skeleton's 31 bones
  ASSERT_EQ(m->jnt_type[0], mjJNT_FREE);
  EXPECT_STREQ(mj_id2name(m, mjOBJ_JOINT, 0), "root");
  const auto hinges = expected_hinges();
  ASSERT_EQ(hinges.size(), 56u);
  for (std::size_t i = 0; i < hinges.size(); ++i) {
    const int j = mj_name2id(m, mjOBJ_JOINT, hinges[i].c_str());
    ASSERT_GE(j, 0) << hinges[i];
    EXPECT_EQ(m->jnt_type[j], mjJNT_HINGE) << hinges[i];
    EXPECT_TRUE(m->jnt_limited[j]) << hinges[i];
    const int a = mj_name2id(m, mjOBJ_ACTUATOR, hinges[i].c_str());
    ASSERT_GE(a, 0) << hinges[i];
    EXPECT_EQ(m->actuator_trnid[2 * a], j) << hinges[i];
    EXPECT_EQ(m->actuator_gear[6 * a], expected_gear(hinges[i])) << hinges[i];
    EXPECT_EQ(m->actuator_ctrlrange[2 * a], -1.0);
    EXPECT_EQ(m->actuator_ctrlrange[2 * a + 1], 1.0);
    // Action a drives observation a: both follow the model's joint order.
    EXPECT_EQ(env.action_spec().names[a], mj_id2name(m, mjOBJ_JOINT, a + 1));
    EXPECT_EQ(env.observation_spec().names[j - 1], hinges[i] + "_angle");
  }
  for (const char* bone : {"root", "lhipjoint", "lfemur", "ltibia", "lfoot", "ltoes", "rhipjoint", "rfemur",
                           "rtibia", "rfoot", "rtoes", "lowerback", "upperback", "thorax", "lowerneck",
                           "upperneck", "head", "lclavicle", "lhumerus", "lradius", "lwrist", "lhand",
                           "lfingers", "lthumb", "rclavicle", "rhumerus", "rradius", "rwrist", "rhand",
                           "rfingers", "rthumb"})
    EXPECT_GE(mj_name2id(m, mjOBJ_BODY, bone), 0) << bone;
  double mass = 0;
  for (int b = 1; b < m->nbody; ++b) mass += m->body_mass[b];
  EXPECT_NEAR(mass, 65.0, 0.5);
  EXPECT_DOUBLE_EQ(m->opt.timestep, 0.005);
  EXPECT_DOUBLE_EQ(env.control_timestep(), 0.03);
  EXPECT_EQ(env.episode_length(), 334);
  EXPECT_EQ(env.obs_dim(), 137);
  EXPECT_EQ(env.act_dim(), 56);
  EXPECT_EQ(env.feature_names().size(), 19u);
}

TEST(Humanoid, StandsInItsRestPoseOnItsFeetAboutOnePointSevenMetresTall) {
  HumanoidEnv env;
  env.reset(0);
  const mjModel* m = env.model();
  const mjData* d = env.data();
  const int head = mj_name2id(m, mjOBJ_GEOM, "head");
  EXPECT_NEAR(d->geom_xpos[3 * head + 2] + m->geom_size[3 * head], 1.70, 0.02);
  EXPECT_GT(d->ncon, 0);
  EXPECT_FALSE(env.off_feet_contact());
  EXPECT_FALSE(env.fallen());
  // The style measures of standing straight with the arms hanging, up to the reset's +- 0.02 rad
  // per hinge: where the gait styles' tuned targets start from.
  const StyleTerms rest = env.style_measures();
  EXPECT_NEAR(rest[kRootHeight], 0.951, 0.03);
  EXPECT_NEAR(rest[kHeadForward], 0.0, 0.03);
  EXPECT_NEAR(rest[kHandHeight], -0.134, 0.03);
  EXPECT_NEAR(rest[kHandSpread], 0.19, 0.03);
  EXPECT_NEAR(rest[kFootSpread], 0.09, 0.03);
}

TEST(Humanoid, StaysUpUnderAPdHoldAndFallsWithoutTorque) {
  const int two_seconds = 67;
  for (std::uint64_t seed : {1, 2, 3}) {
    HumanoidEnv held;
    held.reset(seed);
    std::vector<double> f(held.feature_names().size());
    for (int t = 0; t < two_seconds; ++t) {
      const StepOutcome out = held.step(pd_hold(held).data());
      held.features(f.data());
      ASSERT_FALSE(out.done()) << "seed " << seed << " step " << t;
      ASSERT_EQ(f[3], 0.0);
    }
    EXPECT_GT(held.root_height(), 0.9) << seed;
    EXPECT_GT(held.up_in_root()[2], 0.98) << seed;

    HumanoidEnv limp;
    limp.reset(seed);
    const std::vector<float> zero(HumanoidEnv::kHinges, 0.f);
    StepOutcome out;
    int steps = 0;
    do {
      out = limp.step(zero.data());
      ++steps;
    } while (!out.done());
    limp.features(f.data());
    // The limp body collapses well within two seconds, and the step that ends it is a fall.
    EXPECT_TRUE(out.terminated) << seed;
    EXPECT_LT(steps, two_seconds) << seed;
    EXPECT_EQ(f[3], 1.0) << seed;
  }
}

TEST(Humanoid, ALyingBodyIsFallenByItsContactsAlone) {
  HumanoidOptions o;
  o.terminate_on_fall = false;
  HumanoidEnv env(o);
  env.reset(4);
  const std::vector<float> zero(HumanoidEnv::kHinges, 0.f);
  for (int t = 0; t < 150; ++t) env.step(zero.data());
  EXPECT_TRUE(env.off_feet_contact());
  // Find by hand a floor contact of a geom on neither foot.
  const mjModel* m = env.model();
  const mjData* d = env.data();
  const int floor = mj_name2id(m, mjOBJ_GEOM, "floor");
  bool found = false;
  for (int i = 0; i < d->ncon; ++i) {
    const int other = d->contact[i].geom1 == floor ? d->contact[i].geom2 : d->contact[i].geom1;
    const std::string body = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[other]);
    found = found || (body.find("foot") == std::string::npos && body.find("toes") == std::string::npos);
  }
  EXPECT_TRUE(found);
  EXPECT_TRUE(env.fallen());
}

TEST(Humanoid, SameSeedSameEpisodeBitForBit) {
  HumanoidEnv a, b;
  a.reset(21);
  b.reset(21);
  std::vector<double> fa(a.feature_names().size()), fb(fa.size());
  for (int t = 0; t < 60; ++t) {
    const StepOutcome oa = a.step(hinge_wobble(t).data());
    const StepOutcome ob = b.step(hinge_wobble(t).data());
    EXPECT_EQ(oa.reward, ob.reward);
    EXPECT_EQ(oa.terminated, ob.terminated);
    ASSERT_EQ(a.observation(), b.observation()) << "step " << t;
    a.features(fa.data());
    b.features(fb.data());
    ASSERT_EQ(fa, fb);
  }
  a.reset(21);
  b.reset(22);
  EXPECT_NE(a.observation(), b.observation());
  auto copy = a.clone();
  copy->reset(21);
  EXPECT_EQ(copy->observation(), a.observation());
}

// A humanoid that does not end its episode on a fall, turned (yaw 0.8 rad, then pitch 0.3 rad),
// pushed and stepped, so that no frame is the world's and no velocity is zero (the tests reach
// into the simulator state on purpose).
std::unique_ptr<HumanoidEnv> turned_and_pushed() {
  HumanoidOptions o;
  o.terminate_on_fall = false;
  auto owner = std::make_unique<HumanoidEnv>(o);
  HumanoidEnv& env = *owner;
  env.reset(5);
  auto* d = const_cast<mjData*>(env.data());
  double yaw[4], pitch[4];
  const double z[3] = {0, 0, 1}, y[3] = {0, 1, 0};
  mju_axisAngle2Quat(yaw, z, 0.8);
  mju_axisAngle2Quat(pitch, y, 0.3);
  mju_mulQuat(d->qpos + 3, yaw, pitch);
  d->qpos[2] += 0.3;
  const double push[6] = {0.5, -0.3, 0.2, 0.1, -0.1, 0.2};  // linear (world), angular (root frame)
  std::copy(push, push + 6, d->qvel);
  mj_forward(env.model(), d);
  for (int t = 0; t < 5; ++t) env.step(hinge_wobble(t).data());
  return owner;
}

// A world-frame vector in the frame of the body `root`.
std::vector<double> in_root_frame(const HumanoidEnv& env, int root, const double* world) {
  double out[3];
  mju_mulMatTVec(out, env.data()->xmat + 9 * root, world, 3, 3);
  return std::vector<double>(out, out + 3);
}

TEST(Humanoid, ObservationAndFeaturesMatchTheSimulatorStateByHand) {
  const auto owner = turned_and_pushed();
  const HumanoidEnv& env = *owner;
  const mjData* d = env.data();
  const mjModel* m = env.model();
  const double z[3] = {0, 0, 1};

  const auto obs = env.observation();
  std::vector<double> f(env.feature_names().size());
  env.features(f.data());
  const int root = mj_name2id(m, mjOBJ_BODY, "root");
  const double* r = d->xmat + 9 * root;
  auto in_root = [&](const double* world) { return in_root_frame(env, root, world); };
  for (const auto& hinge : expected_hinges()) {
    const int j = mj_name2id(m, mjOBJ_JOINT, hinge.c_str());
    EXPECT_FLOAT_EQ(obs[j - 1], static_cast<float>(d->qpos[m->jnt_qposadr[j]]));
    EXPECT_FLOAT_EQ(obs[56 + j - 1], static_cast<float>(d->qvel[m->jnt_dofadr[j]]));
  }
  EXPECT_FLOAT_EQ(obs[112], static_cast<float>(d->xpos[3 * root + 2]));
  const auto up = in_root(z);
  EXPECT_GT(std::abs(up[0]), 0.1);  // the pitch shows in the root frame
  double velocity[6];  // angular then linear, at the root's frame origin, in the root frame
  mj_objectVelocity(m, d, mjOBJ_XBODY, root, velocity, 1);
  EXPECT_GT(std::abs(velocity[3]) + std::abs(velocity[4]), 0.1);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(obs[113 + k], up[k], 1e-6);
    EXPECT_NEAR(obs[116 + k], velocity[3 + k], 1e-5);
    EXPECT_NEAR(obs[119 + k], velocity[k], 1e-5);
  }
  for (std::size_t e = 0; e < HumanoidEnv::kEndEffectors.size(); ++e) {
    const char* name = HumanoidEnv::kEndEffectors[e];
    const int body = mj_name2id(m, mjOBJ_BODY, name);
    double offset[3];
    for (int k = 0; k < 3; ++k) offset[k] = d->xpos[3 * body + k] - d->xpos[3 * root + k];
    const auto local = in_root(offset);
    for (int k = 0; k < 3; ++k) {
      const std::string feature = std::string(name) + "_" + "xyz"[k];
      EXPECT_EQ(env.feature_names()[4 + 3 * e + k], feature);
      EXPECT_EQ(env.observation_spec().names[122 + 3 * e + k], feature);
      EXPECT_NEAR(f[4 + 3 * e + k], local[k], 1e-12) << feature;
      EXPECT_FLOAT_EQ(obs[122 + 3 * e + k], static_cast<float>(local[k])) << feature;
    }
  }
  // Heading: the root's x axis (the first column of its rotation) on the floor, turned well away
  // from world x by the yaw.
  const double heading = std::atan2(r[3], r[0]);
  EXPECT_NEAR(f[1], heading, 1e-12);
  EXPECT_GT(heading, 0.3);
  // Forward speed: the centre of mass's velocity, the mass-weighted mean of every body's own.
  double momentum[2] = {0, 0}, mass = 0;
  for (int b = 1; b < m->nbody; ++b) {
    double v[6];
    mj_objectVelocity(m, d, mjOBJ_BODY, b, v, 0);
    for (int k = 0; k < 2; ++k) momentum[k] += m->body_mass[b] * v[3 + k];
    mass += m->body_mass[b];
  }
  EXPECT_NEAR(f[0], (momentum[0] * std::cos(heading) + momentum[1] * std::sin(heading)) / mass, 1e-9);
  EXPECT_NEAR(f[2], d->xpos[3 * root + 2], 1e-12);

  // The style measures: the same centre of mass across the heading, the root's world-frame yaw
  // rate, and the end-effector features averaged over the two sides.
  const double lateral = (-momentum[0] * std::sin(heading) + momentum[1] * std::cos(heading)) / mass;
  double world_velocity[6];
  mj_objectVelocity(m, d, mjOBJ_XBODY, root, world_velocity, 0);
  EXPECT_GT(std::abs(world_velocity[2]), 0.01);
  const StyleTerms s = env.style_measures();
  EXPECT_NEAR(env.lateral_speed(), lateral, 1e-9);
  EXPECT_NEAR(env.yaw_rate(), world_velocity[2], 1e-9);
  EXPECT_NEAR(s[kForwardSpeed], f[0], 1e-12);
  EXPECT_NEAR(s[kSwaySpeed], std::abs(lateral), 1e-9);
  EXPECT_NEAR(s[kTurnRate], std::abs(world_velocity[2]), 1e-9);
  EXPECT_NEAR(s[kRootHeight], f[2], 1e-12);
  EXPECT_NEAR(s[kHeadForward], f[16], 1e-12);                                  // head_x
  EXPECT_NEAR(s[kHandHeight], (f[6] + f[9]) / 2, 1e-12);                        // lhand_z, rhand_z
  EXPECT_NEAR(s[kHandSpread], (std::abs(f[5]) + std::abs(f[8])) / 2, 1e-12);    // lhand_y, rhand_y
  EXPECT_NEAR(s[kFootSpread], (std::abs(f[11]) + std::abs(f[14])) / 2, 1e-12);  // lfoot_y, rfoot_y
}

// The discriminator's subset is what the header says, read off the simulator: the root's height,
// the up axis, the root's velocities, then each end effector's position relative to the root, and
// no joint angle or velocity.
TEST(Humanoid, TheDiscriminatorSeesTheRootAndTheEndEffectorsNotTheJoints) {
  const auto owner = turned_and_pushed();
  const HumanoidEnv& env = *owner;
  const mjModel* m = env.model();
  const mjData* d = env.data();
  const int root = mj_name2id(m, mjOBJ_BODY, "root");
  std::vector<double> expected = {d->xpos[3 * root + 2]};
  const double z[3] = {0, 0, 1};
  const auto up = in_root_frame(env, root, z);
  expected.insert(expected.end(), up.begin(), up.end());
  double velocity[6];  // angular then linear, root frame
  mj_objectVelocity(m, d, mjOBJ_XBODY, root, velocity, 1);
  expected.insert(expected.end(), velocity + 3, velocity + 6);
  expected.insert(expected.end(), velocity, velocity + 3);
  for (const char* name : {"lhand", "rhand", "lfoot", "rfoot", "head"}) {
    const int body = mj_name2id(m, mjOBJ_BODY, name);
    double offset[3];
    for (int k = 0; k < 3; ++k) offset[k] = d->xpos[3 * body + k] - d->xpos[3 * root + k];
    const auto local = in_root_frame(env, root, offset);
    expected.insert(expected.end(), local.begin(), local.end());
  }

  const auto subset = env.discriminator_observation();
  ASSERT_EQ(subset.size(), expected.size());
  const auto obs = env.observation();
  std::vector<double> f(env.feature_names().size());
  env.features(f.data());
  for (size_t k = 0; k < subset.size(); ++k) {
    EXPECT_NEAR(obs.at(subset[k]), expected[k], 1e-5) << env.observation_spec().names[subset[k]];
    EXPECT_GE(subset[k], 2 * HumanoidEnv::kHinges);  // no joint angle or velocity
  }
  // The same coordinates as the features that score imitations (root_height, lhand_x ... head_z).
  EXPECT_FLOAT_EQ(obs[subset[0]], static_cast<float>(f[2]));
  for (int k = 0; k < 15; ++k) EXPECT_FLOAT_EQ(obs[subset[10 + k]], static_cast<float>(f[4 + k]));
  EXPECT_TRUE(make_env(EnvRequest{"walker"})->discriminator_observation().empty());  // the walker's: all of it
}

// The header's formula, by hand: upright * (0.2 + 0.8 * credit(speed, 1, 0.5)) - 0.05 * effort.
TEST(Humanoid, TheRewardPaysForBeingUprightAndMovingForward) {
  const std::vector<float> zero(56, 0.f), full(56, 3.f), half(56, -0.5f);  // full: clipped to 1
  auto reward = [&](double speed, double up_z, const std::vector<float>& a) {
    return HumanoidEnv::upright_forward_reward(speed, up_z, a.data(), 56);
  };
  EXPECT_DOUBLE_EQ(reward(1.0, 1.0, zero), 1.0);                    // upright at 1 m/s: all of it
  EXPECT_NEAR(reward(0.0, 1.0, zero), 0.2 + 0.8 / (1 + 4), 1e-12);  // standing still: 0.36
  EXPECT_NEAR(reward(1.5, 1.0, zero), 0.2 + 0.8 / 2, 1e-12);        // off by the 0.5 m/s scale
  EXPECT_NEAR(reward(0.5, 1.0, zero), 0.2 + 0.8 / 2, 1e-12);        // either way
  EXPECT_NEAR(reward(-1.0, 1.0, zero), 0.2 + 0.8 / (1 + 16), 1e-12);
  EXPECT_NEAR(reward(1.0, 0.0, zero), 0.5, 1e-12);  // lying on the side: half
  EXPECT_NEAR(reward(1.0, -1.0, zero), 0.0, 1e-12);  // upside down: nothing
  EXPECT_NEAR(reward(1.0, 1.0, full), 0.95, 1e-12);
  EXPECT_NEAR(reward(1.0, 1.0, half), 1.0 - 0.05 * 0.25, 1e-12);
}

TEST(Humanoid, StandingStillUprightEarnsTheRewardOfSpeedZero) {
  HumanoidEnv env;
  env.reset(7);
  const std::vector<float> zero(56, 0.f);
  const StepOutcome out = env.step(zero.data());
  const double up_z = env.up_in_root()[2], speed = env.forward_speed();
  ASSERT_GT(up_z, 0.999);
  ASSERT_LT(std::abs(speed), 0.05);
  const double miss = (speed - 1.0) / 0.5;
  EXPECT_NEAR(out.reward, (1 + up_z) / 2 * (0.2 + 0.8 / (1 + miss * miss)), 1e-12);
  EXPECT_NEAR(out.reward, 0.36, 0.015);
}

// The style is a label: any non-negative integer, and the episode is the same bit for bit.
TEST(Humanoid, TheStyleLabelChangesNeitherTheDynamicsNorTheReward) {
  HumanoidEnv zero, ten;
  ten.set_context({10.0});
  EXPECT_EQ(ten.clone()->context(), std::vector<double>{10.0});
  zero.reset(9);
  ten.reset(9);
  ASSERT_EQ(zero.observation(), ten.observation());
  for (int t = 0; t < 60; ++t) {
    const StepOutcome a = zero.step(hinge_wobble(t).data());
    const StepOutcome b = ten.step(hinge_wobble(t).data());
    ASSERT_EQ(a.reward, b.reward) << "step " << t;
    ASSERT_EQ(a.terminated, b.terminated) << "step " << t;
    ASSERT_EQ(zero.observation(), ten.observation()) << "step " << t;
  }
  EXPECT_NO_THROW(ten.set_context({123456.0}));
}

TEST(Humanoid, RefusesAContextThatIsNoStyleLabelInOneLine) {
  HumanoidEnv env;
  env.set_context({4.0});
  const std::vector<std::pair<std::vector<double>, std::string>> malformed = {
      {{-1.0}, "style -1 is no style label"},
      {{0.5}, "style 0.5 is no style label"},
      {{std::nan("")}, "style nan is no style label"},
      {{std::numeric_limits<double>::infinity()}, "style inf is no style label"},
      {{1.0, 2.0}, "context has 2 values, expected 1"},
      {{}, "context has 0 values, expected 1"}};
  for (const auto& [context, needle] : malformed) {
    try {
      env.set_context(context);
      ADD_FAILURE() << needle << ": accepted";
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(needle), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_EQ(env.context(), std::vector<double>{4.0});  // a refused context leaves the last one
  }
}

TEST(Humanoid, IsABuiltInTaskWithAStyleContext) {
  EnvRequest request;
  request.task = "humanoid";
  request.episode_length = 50;
  auto env = make_env(request);
  EXPECT_EQ(env->id(), "humanoid");
  EXPECT_EQ(env->episode_length(), 50);
  EXPECT_EQ(env->context_names(), std::vector<std::string>{"style"});
  env->set_context({3.0});
  EXPECT_THROW(env->set_context({1.0, 2.0}), std::invalid_argument);
  EXPECT_EQ(env->clone()->context(), std::vector<double>{3.0});
  const auto tasks = builtin_tasks();
  EXPECT_NE(std::find(tasks.begin(), tasks.end(), "humanoid"), tasks.end());
}

}  // namespace
}  // namespace vaegail
