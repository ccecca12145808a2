#include "env/generic_task.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "env/registry.h"
#include "env/test_support.h"

namespace vaegail {
namespace {

// A one-legged body standing on its foot: it topples, so it falls.
const std::string kHopper = R"(<mujoco model="tiny_hopper">
  <option timestep="0.005"/>
  <custom>
    <numeric name="vaegail_episode_length" data="50"/>
    <numeric name="vaegail_frame_skip" data="4"/>
    <text name="vaegail_fall_body" data="torso"/>
    <numeric name="vaegail_fall_height" data="FALL_HEIGHT"/>
    <numeric name="vaegail_context_style" data="0.5"/>
  </custom>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="torso" pos="0 0 0.6">
      <joint name="rootx" type="slide" axis="1 0 0"/>
      <joint name="rootz" type="slide" axis="0 0 1"/>
      <joint name="rooty" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 0.2" size="0.05"/>
      <site name="head" pos="0 0 0.2"/>
      <body name="leg">
        <joint name="hip" type="hinge" axis="0 1 0" range="-1 1" limited="true"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.04"/>
      </body>
    </body>
  </worldbody>
  <actuator><motor name="hip_motor" joint="hip" gear="20" ctrllimited="true" ctrlrange="-1 1"/></actuator>
  <sensor>
    <jointpos name="hip_angle" joint="hip"/>
    <framepos name="head_pos" objtype="site" objname="head"/>
  </sensor>
</mujoco>)";

std::string hopper(const std::string& fall_height = "0.3") {
  std::string xml = kHopper;
  xml.replace(xml.find("FALL_HEIGHT"), 11, fall_height);
  return xml;
}

GenericTaskEnv make(const std::string& xml, GenericTaskOptions options = {}) {
  return GenericTaskEnv(MujocoModel::from_xml("tiny_hopper.xml", xml), options);
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  EXPECT_NE(it, names.end()) << name;
  return static_cast<int>(it - names.begin());
}

TEST(GenericTask, TheMjcfsCustomEntriesSetTheTask) {
  const GenericTaskEnv env = make(hopper());
  EXPECT_EQ(env.id(), "tiny_hopper.xml");
  EXPECT_EQ(env.episode_length(), 50);
  EXPECT_DOUBLE_EQ(env.control_timestep(), 0.02);
  EXPECT_EQ(env.feature_names(),
            (std::vector<std::string>{"com_speed", "torso_height", "fallen", "sensor:hip_angle", "sensor:head_pos[0]",
                                      "sensor:head_pos[1]", "sensor:head_pos[2]", "site:head:x", "site:head:y",
                                      "site:head:z"}));
  EXPECT_EQ(env.context_names(), std::vector<std::string>{"style"});
  EXPECT_EQ(env.context(), std::vector<double>{0.5});
  EXPECT_EQ(env.act_dim(), 1);
  EXPECT_EQ(env.obs_dim(), 8);
}

TEST(GenericTask, CommandLineValuesOverrideTheMjcfsAndCloneKeepsThem) {
  GenericTaskOptions o;
  o.frame_skip = 2;
  o.episode_length = 7;
  o.context_names = {"style", "speed"};  // "style" is the MJCF's already
  GenericTaskEnv env = make(hopper(), o);
  EXPECT_DOUBLE_EQ(env.control_timestep(), 0.01);
  EXPECT_EQ(env.context_names(), (std::vector<std::string>{"style", "speed"}));
  env.set_context({1.0, 2.0});
  const auto copy = env.clone();
  EXPECT_DOUBLE_EQ(copy->control_timestep(), 0.01);
  EXPECT_EQ(copy->episode_length(), 7);
  EXPECT_EQ(copy->context(), (std::vector<double>{1.0, 2.0}));
}

TEST(GenericTask, SensorFeaturesDescribeTheStateTheStepReached) {
  GenericTaskEnv env = make(hopper());
  env.reset(3);
  const float push = 1.f;
  for (int t = 0; t < 5; ++t) env.step(&push);
  const auto& names = env.feature_names();
  std::vector<double> f(names.size());
  env.features(f.data());
  const auto obs = env.observation();
  // The head's framepos sensor and its site are the same point; a sensor left from before the
  // integration would lag behind the moving site.
  EXPECT_DOUBLE_EQ(f[index_of(names, "sensor:head_pos[2]")], f[index_of(names, "site:head:z")]);
  EXPECT_DOUBLE_EQ(f[index_of(names, "sensor:head_pos[0]")], f[index_of(names, "site:head:x")]);
  EXPECT_NEAR(f[index_of(names, "sensor:hip_angle")], obs[index_of(env.observation_spec().names, "qpos:hip")], 1e-6);
  EXPECT_DOUBLE_EQ(f[index_of(names, "torso_height")], env.data()->xpos[3 * 1 + 2]);
}

TEST(GenericTask, FallenFollowsTheNamedBodysHeightAndEndsTheEpisode) {
  GenericTaskOptions keep_going;
  keep_going.terminate_on_fall = false;
  keep_going.episode_length = 400;
  GenericTaskEnv env = make(hopper(), keep_going);
  env.reset(1);
  const auto& names = env.feature_names();
  std::vector<double> f(names.size());
  bool fell = false;
  for (int t = 0; t < 400; ++t) {
    const float a = t % 20 < 10 ? 1.f : -1.f;
    env.step(&a);
    env.features(f.data());
    EXPECT_EQ(f[index_of(names, "fallen")], f[index_of(names, "torso_height")] < 0.3 ? 1.0 : 0.0);
    fell = fell || env.fallen();
  }
  EXPECT_TRUE(fell);  // an unsupported one-legged body topples within 8 s
  GenericTaskEnv always = make(hopper("10"));
  always.reset(1);
  const float zero = 0.f;
  const StepOutcome out = always.step(&zero);
  EXPECT_TRUE(out.terminated);
  EXPECT_FALSE(out.truncated);
}

TEST(GenericTask, ResetStartsFromKeyframeZero) {
  std::string xml = hopper();
  xml.replace(xml.find("</mujoco>"), 9, R"(<keyframe><key qpos="0 0.2 0 0.5"/></keyframe></mujoco>)");
  GenericTaskEnv env = make(xml);
  env.reset(0);
  // The key's rootz and hip, each within the +-0.01 reset noise.
  EXPECT_NEAR(env.observation()[1], 0.2, 0.0101);
  EXPECT_NEAR(env.observation()[3], 0.5, 0.0101);
}

TEST(GenericTask, AMissingFallBodyIsNamed) {
  std::string xml = hopper();
  xml.replace(xml.find("data=\"torso\""), 12, "data=\"pelvis\"");
  try {
    make(xml);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tiny_hopper.xml: model has no object named 'pelvis'"), std::string::npos);
  }
}

TEST(GenericTask, TheRegistryBuildsItFromAPathOrFromTheTextItself) {
  EnvRequest request;
  request.task = write_temp("vaegail_tiny_hopper.xml", hopper());
  const auto from_file = make_env(request);
  EXPECT_EQ(from_file->id(), request.task);
  EXPECT_EQ(from_file->episode_length(), 50);
  EXPECT_EQ(from_file->body_mjcf(), hopper());
  request.task = "/nowhere/tiny_hopper.xml";  // the text is used, the path only names it
  request.mjcf_text = hopper();
  const auto from_text = make_env(request);
  EXPECT_EQ(from_text->feature_names(), from_file->feature_names());
}

}  // namespace
}  // namespace vaegail
