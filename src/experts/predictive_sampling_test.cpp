#include "experts/predictive_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "env/humanoid.h"
#include "env/mujoco_env.h"

namespace vaegail {
namespace {

TEST(PredictiveSampling, APlanInterpolatesBetweenKnotsAndHoldsItsLast) {
  // Three knots of two actions, two control steps apart.
  const std::vector<float> plan = {0.0f, 1.0f, 0.4f, -1.0f, 1.0f, 0.0f};
  float a[2];
  PredictiveSampling::plan_action(plan, 3, 2, 2.0, 0.0, a);
  EXPECT_FLOAT_EQ(a[0], 0.0f);
  EXPECT_FLOAT_EQ(a[1], 1.0f);
  PredictiveSampling::plan_action(plan, 3, 2, 2.0, 1.0, a);  // halfway to the second knot
  EXPECT_FLOAT_EQ(a[0], 0.2f);
  EXPECT_FLOAT_EQ(a[1], 0.0f);
  PredictiveSampling::plan_action(plan, 3, 2, 2.0, 3.5, a);  // three quarters to the third
  EXPECT_FLOAT_EQ(a[0], 0.85f);
  EXPECT_FLOAT_EQ(a[1], -0.25f);
  PredictiveSampling::plan_action(plan, 3, 2, 2.0, 9.0, a);  // past the horizon: the last knot
  EXPECT_FLOAT_EQ(a[0], 1.0f);
  EXPECT_FLOAT_EQ(a[1], 0.0f);
}

// A plan of slow sinusoids over the humanoid's 56 motors.
std::vector<float> wavy_plan(int knots) {
  std::vector<float> plan(knots * HumanoidEnv::kHinges);
  for (size_t i = 0; i < plan.size(); ++i) plan[i] = 0.3f * static_cast<float>(std::sin(0.7 * i));
  return plan;
}

TEST(PredictiveSampling, ARolloutScoresWhatTheEnvironmentItselfWouldEarn) {
  HumanoidEnv env;
  env.set_context({2});
  env.reset(3);
  std::vector<float> still(HumanoidEnv::kHinges, 0.1f);
  for (int t = 0; t < 4; ++t) env.step(still.data());  // a state that is not the reset's

  PredictiveSamplingOptions o;
  o.horizon = 7;
  o.knots = 3;
  PredictiveSampling planner(env, o);
  const auto plan = wavy_plan(o.knots);
  const double score = planner.score(env, plan);

  // The same actions on the environment itself: the planner's copy starts from the very state,
  // so every step and reward is the same, to rounding.
  double earned = 0;
  std::vector<float> a(HumanoidEnv::kHinges);
  for (int t = 0; t < o.horizon; ++t) {
    PredictiveSampling::plan_action(plan, o.knots, HumanoidEnv::kHinges, 3.0, t, a.data());
    const StepOutcome out = env.step(a.data());
    ASSERT_FALSE(out.terminated);
    earned += out.reward;
  }
  EXPECT_NEAR(score, earned, 1e-12);
}

TEST(PredictiveSampling, TheSameSeedPlansTheSameActions) {
  HumanoidEnv env;
  env.reset(1);
  PredictiveSamplingOptions o;
  o.samples = 4;
  o.horizon = 4;
  // Standing still is hard to beat from the rest pose; a term paying for the first motor's
  // command makes every perturbed candidate's score differ from the unperturbed one's.
  const auto first_motor = [](const MujocoEnv& e) { return e.data()->ctrl[0]; };
  PredictiveSampling first(env, o), second(env, o);
  first.shaping = second.shaping = first_motor;
  const auto action = first.act(env);
  EXPECT_EQ(action, second.act(env));
  o.seed = 1;
  PredictiveSampling other(env, o);
  other.shaping = first_motor;
  EXPECT_NE(action, other.act(env));
}

TEST(PredictiveSampling, KeepsTheBestCandidateSoItsPlanNeverScoresBelowTheShiftedNominal) {
  HumanoidEnv env;
  env.set_context({0});
  env.reset(4);
  PredictiveSamplingOptions o;
  o.samples = 6;
  o.horizon = 5;
  o.knots = 2;
  PredictiveSampling planner(env, o);
  // From a zero plan the shifted nominal is the zero plan: what the planner keeps must score at
  // least as much as doing nothing, and its first action is the one returned.
  const double nothing = planner.score(env, std::vector<float>(2 * HumanoidEnv::kHinges, 0.0f));
  const auto action = planner.act(env);
  EXPECT_GE(planner.score(env, planner.plan()), nothing);
  float first[HumanoidEnv::kHinges];
  PredictiveSampling::plan_action(planner.plan(), 2, HumanoidEnv::kHinges, 4.0, 0, first);
  EXPECT_EQ(action, std::vector<float>(first, first + HumanoidEnv::kHinges));
}

}  // namespace
}  // namespace vaegail
