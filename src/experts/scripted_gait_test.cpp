#include "experts/scripted_gait.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "env/generic_task.h"

namespace vaegail {
namespace {

// A planar body with a root pitch hinge, a hip about y on the root's child and a knee below it;
// the knee's ctrlrange is asymmetric so that clipping to each actuator's own range shows.
const std::string kBody = R"(<mujoco model="gait_body">
  <compiler angle="radian"/>
  <custom>STYLES</custom>
  <worldbody>
    <body name="torso" pos="0 0 1">
      <joint name="rootx" type="slide" axis="1 0 0"/>
      <joint name="rooty" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.05"/>
      <body name="thigh">
        <joint name="hip" type="hinge" axis="0 1 0" range="-1 1" limited="true"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.04"/>
        <body name="shin" pos="0 0 -0.3">
          <joint name="knee" type="hinge" axis="0 1 0" range="-2 0" limited="true"/>
          <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.03"/>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor name="hip_motor" joint="hip" gear="10" ctrllimited="true" ctrlrange="-1 1"/>
    <motor name="knee_motor" joint="knee" gear="10" ctrllimited="true" ctrlrange="-0.5 2"/>
  </actuator>
</mujoco>)";

std::shared_ptr<const MujocoModel> body(const std::string& styles = "", const std::string& actuators = "") {
  std::string xml = kBody;
  xml.replace(xml.find("STYLES"), 6, styles);
  if (!actuators.empty()) {
    const size_t from = xml.find("<actuator>"), to = xml.find("</actuator>") + 11;
    xml.replace(from, to - from, actuators);
  }
  return MujocoModel::from_xml("gait_body.xml", xml);
}

GaitStyle style(double frequency, std::vector<double> amplitude, std::vector<double> offset,
                std::vector<double> phase) {
  GaitStyle s;
  s.name = "test";
  s.frequency = frequency;
  s.kp = 3.0;
  s.kd = 0.5;
  s.pitch_kp = 2.0;
  s.pitch_kd = 0.25;
  s.lean = 0.1;
  s.amplitude = std::move(amplitude);
  s.offset = std::move(offset);
  s.phase = std::move(phase);
  return s;
}

TEST(ScriptedGait, PdTorqueWithBalanceOnTheHipMatchesAHandComputation) {
  const auto model = body();
  const mjModel* m = model->get();
  const ScriptedGait gait(m, "gait_body.xml", {style(2.0, {0.2, 0.3}, {0.1, -0.8}, {0.0, 1.0})});
  ASSERT_EQ(gait.balance_actuators(), std::vector<int>{0});  // the hip, not the knee

  // qpos: rootx, rooty, hip, knee; qvel the same.
  const double qpos[] = {5.0, 0.2, 0.05, -0.7}, qvel[] = {1.0, -0.4, 0.3, 0.2};
  const double t = 0.1;  // 2 Hz: angle 0.4 pi
  double ctrl[2];
  gait.control(0, t, qpos, qvel, ctrl);
  const double hip_target = 0.1 + 0.2 * std::sin(0.4 * M_PI);
  const double hip = 3.0 * (hip_target - 0.05) - 0.5 * 0.3 + 2.0 * (0.2 - 0.1) + 0.25 * (-0.4);
  const double knee_target = -0.8 + 0.3 * std::sin(0.4 * M_PI + 1.0);
  const double knee = 3.0 * (knee_target - (-0.7)) - 0.5 * 0.2;
  EXPECT_NEAR(ctrl[0], hip, 1e-12);
  EXPECT_NEAR(ctrl[1], knee, 1e-12);
  ASSERT_LT(std::abs(hip), 1.0);  // the hand values lie inside the ranges: nothing was clipped
  ASSERT_GT(knee, -0.5);
}

TEST(ScriptedGait, ClipsToEachActuatorsCtrlrange) {
  const auto model = body();
  const ScriptedGait gait(model->get(), "gait_body.xml", {style(1.0, {0, 0}, {0, 0}, {0, 0})});
  const double qvel[] = {0, 0, 0, 0};
  double ctrl[2];
  const double far_below[] = {0, 0, -3, -3};  // errors +3 rad: kp 3 asks for 9
  gait.control(0, 0, far_below, qvel, ctrl);
  EXPECT_EQ(ctrl[0], 1.0);
  EXPECT_EQ(ctrl[1], 2.0);
  const double far_above[] = {0, 0, 3, 3};
  gait.control(0, 0, far_above, qvel, ctrl);
  EXPECT_EQ(ctrl[0], -1.0);
  EXPECT_EQ(ctrl[1], -0.5);
}

TEST(ScriptedGait, RejectsActuatorsThatAreNotMotorsOnHinges) {
  const auto slide = body("", R"(<actuator><motor name="push" joint="rootx"/></actuator>)");
  try {
    ScriptedGait(slide->get(), "gait_body.xml", {});
    FAIL() << "a motor on a slide joint was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("gait_body.xml: actuator 'push' is not a motor on a hinge joint"),
              std::string::npos);
  }
  const auto servo = body("", R"(<actuator><position name="servo" joint="hip" kp="10"/></actuator>)");
  EXPECT_THROW(ScriptedGait(servo->get(), "gait_body.xml", {}), std::invalid_argument);
  const auto model = body();
  EXPECT_THROW(ScriptedGait(model->get(), "gait_body.xml", {style(1.0, {0.1}, {0, 0}, {0, 0})}),
               std::invalid_argument);  // one amplitude for two actuators
}

TEST(GaitStyles, ReadsTheMjcfsStylesInOrderAndCountsThem) {
  const auto model = body(R"(
    <numeric name="vaegail_gait_style_slow" data="1 2 0.1 0.5 0.05 -0.1  0.2 0 0  0.3 -1 1.5"/>
    <numeric name="vaegail_gait_style_fast" data="3 4 0.2 0 0 0  0.4 0.1 0.5  0.6 -0.5 2"/>)");
  const auto styles = gait_styles(model->get(), "gait_body.xml", 2, 0);
  ASSERT_EQ(styles.size(), 2u);
  EXPECT_EQ(styles[0].name, "slow");
  EXPECT_EQ(styles[0].frequency, 1);
  EXPECT_EQ(styles[0].kp, 2);
  EXPECT_EQ(styles[0].kd, 0.1);
  EXPECT_EQ(styles[0].pitch_kp, 0.5);
  EXPECT_EQ(styles[0].pitch_kd, 0.05);
  EXPECT_EQ(styles[0].lean, -0.1);
  EXPECT_EQ(styles[0].amplitude, (std::vector<double>{0.2, 0.3}));
  EXPECT_EQ(styles[0].offset, (std::vector<double>{0, -1}));
  EXPECT_EQ(styles[0].phase, (std::vector<double>{0, 1.5}));
  EXPECT_EQ(styles[1].name, "fast");
  EXPECT_EQ(styles[1].phase, (std::vector<double>{0.5, 2}));
  EXPECT_EQ(gait_styles(model->get(), "gait_body.xml", 1, 0).size(), 1u);
  EXPECT_THROW(gait_styles(model->get(), "gait_body.xml", 3, 0), std::invalid_argument);
  EXPECT_THROW(gait_styles(model->get(), "gait_body.xml", 0, 0), std::invalid_argument);
  const auto short_style = body(R"(<numeric name="vaegail_gait_style_bad" data="1 2 3"/>)");
  EXPECT_THROW(gait_styles(short_style->get(), "gait_body.xml", 1, 0), std::invalid_argument);
}

TEST(GaitStyles, DrawnFromTheSeedWithinTheJointRanges) {
  const auto model = body();
  const GaitKnobs knobs;
  auto drawn = [&](std::uint64_t seed) { return gait_styles(model->get(), "gait_body.xml", 4, seed); };
  const auto a = drawn(7), again = drawn(7), other = drawn(8);
  ASSERT_EQ(a.size(), 4u);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].frequency, again[k].frequency);
    EXPECT_EQ(a[k].amplitude, again[k].amplitude);
    EXPECT_NE(a[k].frequency, other[k].frequency);
    EXPECT_GE(a[k].frequency, knobs.min_frequency);
    EXPECT_LE(a[k].frequency, knobs.max_frequency);
    // The knee's range is [-2, 0]: half range 1 about -1.
    EXPECT_GE(a[k].amplitude[1], knobs.min_amplitude);
    EXPECT_LE(a[k].amplitude[1], knobs.max_amplitude);
    EXPECT_NEAR(a[k].offset[1], -1.0, knobs.max_offset);
  }
  EXPECT_NE(a[0].frequency, a[1].frequency);
}

// The tutorial's hopper (docs/own_body/hopper.xml) and its four styles, 8 episodes each.
struct HopperRollout {
  std::vector<GaitStyle> styles;
  std::vector<Episode> episodes;
  std::vector<int> style_of_episode;
};

HopperRollout hopper_rollout(std::uint64_t seed) {
  GenericTaskOptions options;
  options.context_names = {"style"};
  const GenericTaskEnv env(MujocoModel::from_file(std::string(VAEGAIL_SOURCE_DIR) + "/docs/own_body/hopper.xml"),
                           options);
  HopperRollout r;
  r.styles = gait_styles(env.model(), env.id(), 4, seed);
  RecordRequest request;
  for (int i = 0; i < 32; ++i) {
    request.seeds.push_back(derive_seed(seed, i));
    request.contexts.push_back({static_cast<double>(i % 4)});
    r.style_of_episode.push_back(i % 4);
  }
  const auto gait = std::make_shared<const ScriptedGait>(env.model(), env.id(), r.styles);
  r.episodes = record_episodes(env, request, scripted_gait_policy(gait, env, r.style_of_episode));
  return r;
}

TEST(ScriptedGait, HopperStylesDifferInSpeedAndNoneFalls) {
  const HopperRollout r = hopper_rollout(1);
  std::map<std::string, double> speed;
  for (size_t i = 0; i < r.episodes.size(); ++i) {
    const Episode& e = r.episodes[i];
    EXPECT_FALSE(e.terminations.back()) << "episode " << i << " fell";
    EXPECT_EQ(e.context, std::vector<double>{static_cast<double>(r.style_of_episode[i])});
    speed[r.styles[r.style_of_episode[i]].name] += e.attributes.at("mean_com_speed") / 8;
  }
  // Over the page's 2 s episodes, from standing: bob stays, shuffle and hop go forwards, back backwards.
  EXPECT_LT(std::abs(speed["bob"]), 0.05);
  EXPECT_GT(speed["shuffle"], 0.05);
  EXPECT_GT(speed["hop"], speed["shuffle"] + 0.1);
  EXPECT_LT(speed["back"], -0.1);
}

TEST(ScriptedGait, SameSeedGivesTheSameEpisodesBitForBit) {
  const HopperRollout a = hopper_rollout(3), b = hopper_rollout(3), c = hopper_rollout(4);
  ASSERT_EQ(a.episodes.size(), b.episodes.size());
  for (size_t i = 0; i < a.episodes.size(); ++i) {
    EXPECT_EQ(a.episodes[i].observations, b.episodes[i].observations);
    EXPECT_EQ(a.episodes[i].actions, b.episodes[i].actions);
  }
  EXPECT_NE(a.episodes[0].observations, c.episodes[0].observations);  // another seed, other resets
}

}  // namespace
}  // namespace vaegail
