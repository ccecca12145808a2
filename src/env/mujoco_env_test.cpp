#include "env/mujoco_env.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "env/embedded_models.h"
#include "env/humanoid.h"
#include "env/registry.h"
#include "env/walker.h"
#include "env/test_support.h"

namespace vaegail {
namespace {

const char* kPendulum = R"(<mujoco>
  <worldbody>
    <body name="pole">
      <joint name="hinge" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -1" size="0.05"/>
    </body>
  </worldbody>
  <actuator><motor name="torque" joint="hinge" ctrllimited="true" ctrlrange="-2 2"/></actuator>
</mujoco>)";

TEST(MujocoEnv, AnyMjcfFileLoadsThroughTheSameWrapper) {
  EnvRequest request;
  request.task = write_temp("vaegail_pendulum.xml", kPendulum);
  request.frame_skip = 5;
  request.episode_length = 10;
  auto env = make_env(request);
  EXPECT_EQ(env->obs_dim(), 2);
  EXPECT_EQ(env->observation_spec().names[0], "qpos:hinge");
  EXPECT_EQ(env->observation_spec().names[1], "qvel:hinge");
  EXPECT_EQ(env->action_spec().names[0], "torque");
  EXPECT_DOUBLE_EQ(env->action_spec().high[0], 2.0);
  EXPECT_DOUBLE_EQ(env->control_timestep(), 0.002 * 5);
  env->reset(1);
  const float push = 2.f;
  StepOutcome out;
  for (int t = 0; t < 10; ++t) out = env->step(&push);
  EXPECT_TRUE(out.truncated);
  EXPECT_GT(env->observation()[1], 0.05f);  // 2 Nm on ~2.6 kg m^2 for 0.1 s: ~0.077 rad/s
}

TEST(MujocoEnv, MissingOrBrokenModelsNameTheFile) {
  EnvRequest request;
  request.task = "/nonexistent/body.xml";
  try {
    make_env(request);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/body.xml"), std::string::npos);
  }
  request.task = write_temp("vaegail_broken.xml", "<mujoco><worldbody><body>");
  EXPECT_THROW(make_env(request), std::runtime_error);
  request.task = "no_such_task";
  EXPECT_THROW(make_env(request), std::invalid_argument);
}

TEST(MujocoEnv, WalkerModelIsEmbedded) {
  EXPECT_NE(embedded_model("walker.xml").find("vaegail_walker"), std::string::npos);
  EXPECT_THROW(embedded_model("nothing.xml"), std::out_of_range);
}

TEST(MujocoEnv, SetStateObservesAnotherSimulationAfterItsSteps) {
  WalkerEnv source, copy;
  source.reset(4);
  copy.reset(5);
  const float action[6] = {0.8f, -0.5f, 0.3f, -0.9f, 0.6f, -0.2f};
  for (int t = 0; t < 20; ++t) source.step(action);
  // After mj_step the source's kinematics are refreshed by its own step(); a user's mjData
  // would hold those of the state before: set_state must not rely on them.
  mjData* stale = mj_makeData(source.model());
  mj_copyData(stale, source.model(), source.data());
  mju_zero(stale->xpos, 3 * source.model()->nbody);
  copy.set_state(source.model(), stale);
  EXPECT_EQ(copy.observation(), source.observation());
  std::vector<double> a(3), b(3);
  source.features(a.data());
  copy.features(b.data());
  EXPECT_EQ(a, b);
  mj_deleteData(stale);
}

TEST(MujocoEnv, SetStateRejectsAnotherModelNamingIt) {
  EnvRequest request;
  request.task = write_temp("vaegail_pendulum.xml", kPendulum);
  auto pendulum = make_env(request);
  WalkerEnv walker;
  try {
    walker.set_state(dynamic_cast<MujocoEnv&>(*pendulum).model(), dynamic_cast<MujocoEnv&>(*pendulum).data());
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("walker.xml: the simulation's model has nq/nv/na/nu 1/1/0/1"),
              std::string::npos) << e.what();
  }
}


// Writes the same ctrl before every physics step: what step() does with a held action.
class HeldCtrlController : public PhysicsStepController {
 public:
  explicit HeldCtrlController(std::vector<double> ctrl) : ctrl_(std::move(ctrl)) {}
  void control(const mjModel* m, mjData* d) override { std::copy_n(ctrl_.begin(), m->nu, d->ctrl); }

 private:
  std::vector<double> ctrl_;
};

// Writes `first` and `second` on alternate physics steps.
class AlternatingCtrlController : public PhysicsStepController {
 public:
  AlternatingCtrlController(double first, double second) : values_{first, second} {}
  void control(const mjModel* m, mjData* d) override {
    for (int a = 0; a < m->nu; ++a) d->ctrl[a] = values_[calls_ % 2];
    ++calls_;
  }

 private:
  double values_[2];
  int calls_ = 0;
};

// Pulls the hinge towards 0 from its state: what it applies depends on where the step starts.
class PdController : public PhysicsStepController {
 public:
  void control(const mjModel* m, mjData* d) override {
    for (int a = 0; a < m->nu; ++a) d->ctrl[a] = -3.0 * d->qpos[0] - 0.5 * d->qvel[0];
  }
};

std::shared_ptr<Env> pendulum_env(int frame_skip) {
  EnvRequest request;
  request.task = write_temp("vaegail_pendulum.xml", kPendulum);
  request.frame_skip = frame_skip;
  return make_env(request);
}

TEST(MujocoEnvStepControlled, AConstantControllerRecordsItsConstantAsTheMeanAction) {
  auto env = pendulum_env(5);
  env->reset(1);
  HeldCtrlController held({1.25});
  float mean = 0;
  dynamic_cast<MujocoEnv&>(*env).step_controlled(held, &mean);
  EXPECT_FLOAT_EQ(mean, 1.25f);
}

TEST(MujocoEnvStepControlled, AlternatingValuesRecordTheirMeanAndOutOfRangeCtrlIsClippedAsApplied) {
  auto env = pendulum_env(4);  // an even count: two of each value
  auto& mj = dynamic_cast<MujocoEnv&>(*env);
  env->reset(1);
  AlternatingCtrlController alternating(1.5, -0.5);
  float mean = 0;
  mj.step_controlled(alternating, &mean);
  EXPECT_FLOAT_EQ(mean, 0.5f);
  AlternatingCtrlController beyond(5.0, 1.0);  // ctrlrange is [-2, 2]: 5 is applied as 2
  mj.step_controlled(beyond, &mean);
  EXPECT_FLOAT_EQ(mean, 1.5f);
  EXPECT_DOUBLE_EQ(mj.data()->ctrl[0], 1.0);
}

TEST(MujocoEnvStepControlled, TheLookaheadIsTheMeanTheStepWillRecordAndLeavesTheSimulationWhereItWas) {
  auto env = pendulum_env(5);
  auto& mj = dynamic_cast<MujocoEnv&>(*env);
  env->reset(3);
  const float push = 1.5f;
  env->step(&push);  // away from rest, moving
  PdController pd;
  const auto state = [&] {
    const mjData* d = mj.data();
    return std::vector<double>{d->qpos[0], d->qvel[0], d->time, d->ctrl[0]};
  };
  const auto before = state();
  float ahead = 0, applied = 0;
  mj.lookahead_controlled(pd, &ahead);
  EXPECT_EQ(state(), before);
  mj.step_controlled(pd, &applied);
  EXPECT_EQ(ahead, applied);
  EXPECT_NE(applied, 0.0f);
  mj.lookahead_controlled(pd, &ahead);  // from the new state: another mean
  EXPECT_NE(ahead, applied);
  mj.step_controlled(pd, &applied);
  EXPECT_EQ(ahead, applied);
}

TEST(MujocoEnvStepControlled, AConstantControllerStepsTheHumanoidExactlyAsStepWithTheHeldAction) {
  HumanoidEnv stepped, controlled;
  stepped.reset(7);
  controlled.reset(7);
  std::vector<float> action(stepped.act_dim());
  for (size_t a = 0; a < action.size(); ++a) action[a] = 0.3f * std::sin(0.7f * a);  // a pose-holding guess, not 0
  HeldCtrlController held(std::vector<double>(action.begin(), action.end()));
  std::vector<float> mean(action.size());
  std::vector<double> a(stepped.feature_names().size()), b(a.size());
  for (int t = 0; t < 40; ++t) {
    const StepOutcome x = stepped.step(action.data());
    const StepOutcome y = controlled.step_controlled(held, mean.data());
    ASSERT_EQ(mean, action) << t;
    ASSERT_EQ(x.reward, y.reward) << t;
    ASSERT_EQ(x.terminated, y.terminated) << t;
    ASSERT_EQ(x.truncated, y.truncated) << t;
    stepped.features(a.data());
    controlled.features(b.data());
    ASSERT_EQ(a, b) << t;
    ASSERT_EQ(stepped.observation(), controlled.observation()) << t;
    if (x.done()) break;
  }
}

}  // namespace
}  // namespace vaegail
