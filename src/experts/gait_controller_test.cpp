// The gait controller's pieces against hand-computed answers: gravity compensation, the
// placement law, the swing leg's IK, the state machine, and its parameter files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "env/embedded_models.h"
#include "env/mujoco_model.h"
#include "experts/balance_feedback.h"
#include "experts/gait_parameters.h"
#include "experts/gait_skeleton.h"
#include "experts/gait_state_machine.h"
#include "experts/swing_ik.h"
#include "experts/virtual_model.h"
#include "util/rng.h"

namespace vaegail {
namespace {

std::string xml_with_replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// The humanoid with its pelvis fixed in the air (no free joint), joint limits and contacts off:
// every hinge can be posed anywhere and only gravity and the applied torques act.
std::shared_ptr<const MujocoModel> pinned_humanoid() {
  std::string xml = xml_with_replaced(embedded_model("humanoid_cmu.xml"), "<freejoint name=\"root\"/>", "");
  xml = xml_with_replaced(xml, "<option timestep=\"0.005\"/>",
                 "<option timestep=\"0.005\"><flag contact=\"disable\" limit=\"disable\"/></option>");
  return MujocoModel::from_xml("pinned_humanoid.xml", xml);
}

TEST(GaitVirtualModel, HipTorquesFromGravityTorqueHoldAPosedHangingLegStill) {
  const auto model = pinned_humanoid();
  const mjModel* m = model->get();
  MjDataPtr d(mj_makeData(m));
  Rng rng(3);
  for (int j = 0; j < m->njnt; ++j) d->qpos[m->jnt_qposadr[j]] = rng.uniform(-0.6, 0.6);  // velocities stay 0
  mj_forward(m, d.get());
  const GaitSkeleton skeleton(m, "pinned");
  const GaitLeg& leg = skeleton.legs[0];
  const double* a0 = d->xaxis + 3 * leg.hip_rz;
  const double* a1 = d->xaxis + 3 * leg.hip_ry;
  const double* a2 = d->xaxis + 3 * leg.hip_rx;
  // Posed far from rest the hip's axes are not orthogonal: solving A f = tau would not hold it.
  ASSERT_GT(std::abs(mju_dot3(a0, a2)), 0.05);
  // Every other hinge carries its own load (qfrc_bias); the hip holds the whole leg hanging from
  // it, exerting on it the opposite of gravity's torque about the hip.
  for (int v = 0; v < m->nv; ++v) d->qfrc_applied[v] = d->qfrc_bias[v];
  Vec3 hold = gravity_torque(m, d.get(), leg.femur, d->xanchor + 3 * leg.hip_rx);
  for (double& x : hold) x = -x;
  const Vec3 hips = hinge_torques(a0, a1, a2, hold);
  const int joints[3] = {leg.hip_rz, leg.hip_ry, leg.hip_rx};
  for (int k = 0; k < 3; ++k) d->qfrc_applied[m->jnt_dofadr[joints[k]]] = hips[k];
  mj_forward(m, d.get());
  for (int v = 0; v < m->nv; ++v) EXPECT_NEAR(d->qacc[v], 0.0, 1e-8) << mj_id2name(m, mjOBJ_JOINT, m->dof_jntid[v]);
}

TEST(GaitVirtualModel, SupportTorqueIsTheWeightOfTheRestTimesItsLeverAboutTheStanceHip) {
  const auto model = MujocoModel::from_xml("humanoid_cmu.xml", embedded_model("humanoid_cmu.xml"));
  const mjModel* m = model->get();
  MjDataPtr d(mj_makeData(m));
  mj_forward(m, d.get());  // the rest pose
  const GaitSkeleton skeleton(m, "humanoid");
  const GaitLeg& stance = skeleton.legs[0];
  // By hand: the mass and centre of mass of every body outside the left leg.
  double mass = 0, com[3] = {0, 0, 0};
  for (int b = 1; b < m->nbody; ++b) {
    bool in_leg = false;
    for (int a = b; a > 0; a = m->body_parentid[a]) in_leg = in_leg || a == stance.femur;
    if (in_leg) continue;
    mass += m->body_mass[b];
    for (int k = 0; k < 3; ++k) com[k] += m->body_mass[b] * d->xipos[3 * b + k];
  }
  for (double& c : com) c /= mass;
  const double* hip = d->xanchor + 3 * stance.hip_rx;
  const Vec3 t = support_torque(m, d.get(), skeleton.root, stance.femur, hip);
  const double weight = 9.81 * mass;
  // The rest hangs over the right of the left hip and ahead or behind it: the leg pushes it back
  // up, about +x on the leg when the rest is to its right.
  EXPECT_NEAR(t[0], -(com[1] - hip[1]) * weight, 1e-9);
  EXPECT_NEAR(t[1], (com[0] - hip[0]) * weight, 1e-9);
  EXPECT_NEAR(t[2], 0.0, 1e-9);
  EXPECT_GT(t[0], 0.0);
}

TEST(GaitVirtualModel, OrientationErrorIsTheRotationVectorBetweenTwoOrientations) {
  const Mat3 current = rotation_y(0.3);
  const Mat3 target = multiply(rotation_z(0.2), current);  // 0.2 rad about world z from current
  const Vec3 e = orientation_error(target, current.data());
  EXPECT_NEAR(e[0], 0.0, 1e-12);
  EXPECT_NEAR(e[1], 0.0, 1e-12);
  EXPECT_NEAR(e[2], 0.2, 1e-12);
}

TEST(GaitBalanceFeedback, FootPlacementByHand) {
  GaitParameters p;
  p.place_dx = 1.0, p.place_vx = 0.2, p.speed = 1.5, p.place_offset_x = 0.05;
  p.place_dy = 0.9, p.place_vy = 0.3, p.sway_speed = 0.1, p.step_width = 0.1;
  // Heading +y: the heading frame's x is world y, its y is world -x.
  const Vec2 target = foot_placement(p, {1.0, 2.0}, {0.9, 2.1}, {-0.2, 1.0}, M_PI / 2, +1.0);
  // d = (0.1, 0.1), v = (1.0, 0.2) in the heading frame;
  // x_f = 0.1 + 0.2 (1.0 - 1.5) + 0.05 = 0.05, y_f = 0.9 * 0.1 + 0.3 (0.2 - 0.1) + 0.1 = 0.22.
  EXPECT_NEAR(target[0], 1.0 - 0.22, 1e-12);
  EXPECT_NEAR(target[1], 2.0 + 0.05, 1e-12);
  // The right leg swinging mirrors the lateral terms: y_f = 0.09 + 0.3 (0.2 + 0.1) - 0.1 = 0.08.
  EXPECT_NEAR(foot_placement(p, {1.0, 2.0}, {0.9, 2.1}, {-0.2, 1.0}, M_PI / 2, -1.0)[0], 1.0 - 0.08, 1e-12);
}

TEST(GaitBalanceFeedback, CommandedHeadingTurnsAtTheTurnRateAndWandersAboutTheHeading) {
  GaitParameters p;
  p.heading = -0.2, p.turn_rate = 0.1, p.heading_wander = 0.3, p.wander_period = 4.0;
  EXPECT_NEAR(commanded_heading(p, 0.0), 0.0, 1e-12);         // the reset's facing
  EXPECT_NEAR(commanded_heading(p, 1.0), -0.1 + 0.3, 1e-12);  // halfway through the turn, the wander at its peak
  EXPECT_NEAR(commanded_heading(p, 3.0), -0.2 - 0.3, 1e-12);  // turned
  EXPECT_NEAR(commanded_heading(p, 4.0), -0.2, 1e-12);
}

TEST(GaitSwingIk, TheLegItSolvesForReachesTheTargetWithTheKneeForward) {
  const Vec3 hip = {0.3, -0.1, 0.9};
  const double thigh = 0.417, shank = 0.418;
  for (const double heading : {0.0, 0.7, -2.0}) {
    const Vec3 forward = {std::cos(heading), std::sin(heading), 0};
    for (const Vec3& offset : std::vector<Vec3>{{0.2, 0.05, -0.7}, {-0.3, -0.1, -0.6}, {0.05, 0.2, -0.4}, {0.4, 0.0, -0.5}}) {
      const Vec3 target = {hip[0] + offset[0], hip[1] + offset[1], hip[2] + offset[2]};
      const LegPose pose = two_link_ik(hip, target, forward, thigh, shank);
      const Vec3 reached = ankle_position(pose, hip, thigh, shank);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(reached[k], target[k], 1e-9) << heading;
      EXPECT_GT(pose.knee, 0.0);
      // The knee (hip minus the thigh along the femur's z) lies ahead of the hip-to-ankle line.
      const Vec3 knee = {hip[0] - thigh * pose.femur[2], hip[1] - thigh * pose.femur[5], hip[2] - thigh * pose.femur[8]};
      const Vec3 mid = {0.5 * (hip[0] + target[0]), 0.5 * (hip[1] + target[1]), 0.5 * (hip[2] + target[2])};
      EXPECT_GT((knee[0] - mid[0]) * forward[0] + (knee[1] - mid[1]) * forward[1], 0.0);
    }
  }
  // Out of reach: the leg points at the target, straight but for the 0.5% margin.
  const Vec3 far = {hip[0], hip[1], hip[2] - 2.0};
  const Vec3 reached = ankle_position(two_link_ik(hip, far, {1, 0, 0}, thigh, shank), hip, thigh, shank);
  EXPECT_NEAR(reached[0], hip[0], 1e-9);
  EXPECT_NEAR(reached[2], hip[2] - 0.995 * (thigh + shank), 1e-9);
}

TEST(GaitSwingIk, SwingPathLiftsAtTheStartReachesTheTargetAndEndsBelowStandingHeight) {
  GaitParameters p;
  p.swing_height = 0.15, p.swing_descent_phase = 0.8, p.swing_reach_phase = 0.7, p.swing_end_height = -0.05;
  const Vec2 lift_off = {0.0, 0.1}, target = {0.5, 0.2};
  const double ankle = 0.066;
  const Vec3 start = swing_ankle_path(p, lift_off, target, 0.0, ankle);
  EXPECT_NEAR(start[0], 0.0, 1e-12);
  EXPECT_NEAR(start[2], ankle, 1e-12);
  const Vec3 top = swing_ankle_path(p, lift_off, target, 0.4, ankle);
  EXPECT_NEAR(top[2], ankle + 0.15, 1e-12);
  EXPECT_NEAR(swing_ankle_path(p, lift_off, target, 0.35, ankle)[0], 0.25, 1e-12);  // halfway at half the reach phase
  const Vec3 over = swing_ankle_path(p, lift_off, target, 0.7, ankle);
  EXPECT_NEAR(over[0], 0.5, 1e-12);
  EXPECT_NEAR(over[1], 0.2, 1e-12);
  EXPECT_NEAR(swing_ankle_path(p, lift_off, target, 0.8, ankle)[2], ankle, 1e-12);
  EXPECT_NEAR(swing_ankle_path(p, lift_off, target, 1.0, ankle)[2], ankle - 0.05, 1e-12);
  EXPECT_LT(swing_ankle_path(p, lift_off, target, 1.2, ankle)[2], ankle - 0.05);
}

TEST(GaitStateMachine, SwapsOnContactAfterTheMinimumTimeOrAtTheMaximum) {
  const double dt = 0.005, min_time = 0.3, max_time = 0.45;
  GaitStateMachine scuff;
  for (int k = 0; k < 50; ++k) EXPECT_FALSE(scuff.advance(dt, true, min_time, max_time)) << k;  // 0.25 s < min_time
  EXPECT_EQ(scuff.stance(), GaitStateMachine::kLeft);

  GaitStateMachine landing;
  for (int k = 0; k < 70; ++k) landing.advance(dt, false, min_time, max_time);  // 0.35 s in the air
  EXPECT_TRUE(landing.advance(dt, true, min_time, max_time));
  EXPECT_EQ(landing.stance(), GaitStateMachine::kRight);
  EXPECT_EQ(landing.time_in_step(), 0.0);
  EXPECT_EQ(landing.steps(), 1);

  GaitStateMachine hanging;
  int swapped_at = -1;
  for (int k = 1; k <= 100 && swapped_at < 0; ++k)
    if (hanging.advance(dt, false, min_time, max_time)) swapped_at = k;
  EXPECT_EQ(swapped_at, 90);  // 90 x 0.005 s = max_time, no contact
  EXPECT_EQ(hanging.swing(), GaitStateMachine::kLeft);
}

TEST(GaitParametersJson, PartialJsonTakesTheDefaultsAndATunerSetsAKnobByName) {
  const GaitParameters defaults;
  const auto p = gait_parameters_from_json({{"speed", 0.8}, {"elbow", 1.2}}, "test");
  EXPECT_EQ(p.speed, 0.8);
  EXPECT_EQ(p.elbow, 1.2);
  EXPECT_EQ(p.place_dx, defaults.place_dx);
  nlohmann::json j = p;  // the tuner's round trip: every knob a top-level number
  for (const auto& [key, value] : j.items()) EXPECT_TRUE(value.is_number()) << key;
  j["step_width"] = 0.15;
  EXPECT_EQ(j.get<GaitParameters>().step_width, 0.15);
  EXPECT_EQ(j.get<GaitParameters>().speed, 0.8);
}

TEST(GaitParametersJson, UnknownKeysAndImpossibleTimesAreOneLineErrors) {
  try {
    gait_parameters_from_json({{"sped", 1.0}}, "walk.json");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "walk.json: 'sped' is not a gait parameter");
  }
  EXPECT_THROW(gait_parameters_from_json({{"step_min_time", 0.0}}, "x"), std::invalid_argument);
  EXPECT_THROW(gait_parameters_from_json({{"swing_descent_phase", 1.5}}, "x"), std::invalid_argument);
  EXPECT_THROW(gait_parameters_from_json({{"speed", "fast"}}, "x"), std::invalid_argument);
}

TEST(GaitParametersJson, StyleFilesReadTheirParametersAndLeaveOtherKeysAlone) {
  const std::string path = testing::TempDir() + "vaegail_gait_style.json";
  std::ofstream(path) << R"({"tuning": {"generation": 12, "score": 40.5}, "parameters": {"back_pitch": 0.4}})";
  EXPECT_EQ(read_gait_style(path).back_pitch, 0.4);
  std::ofstream(path) << R"({"back_pitch": 0.4})";
  EXPECT_THROW(read_gait_style(path), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail
