#include "eval/body_eval.h"

#include <gtest/gtest.h>

#include "data/record.h"
#include "env/generic_task.h"

namespace vaegail::eval {
namespace {

// A pendulum whose tip site is a feature; it "falls" when the tip drops below -0.9.
const char* const kPendulum = R"(<mujoco model="pendulum">
  <custom>
    <numeric name="vaegail_episode_length" data="30"/>
    <numeric name="vaegail_frame_skip" data="5"/>
  </custom>
  <worldbody>
    <body name="pole">
      <joint name="hinge" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -1" size="0.05"/>
      <site name="tip" pos="0 0 -1"/>
    </body>
  </worldbody>
  <actuator><motor name="torque" joint="hinge" ctrllimited="true" ctrlrange="-1 1" gear="5"/></actuator>
</mujoco>)";

GenericTaskEnv pendulum() { return GenericTaskEnv(MujocoModel::from_xml("pendulum.xml", kPendulum), {}); }

DemoSet push_demos(const Env& env) {
  DemoSet demos{"push", header_for(env), {}};
  RecordRequest r;
  r.expert_id = "push";
  r.seeds = {1, 2};
  const BatchPolicy push = [](int n, const float*, const int*, const int*, float* a) { std::fill(a, a + n, 1.f); };
  demos.episodes = record_episodes(env, r, push);
  return demos;
}

torch::Tensor push_actions(const torch::Tensor& obs, const torch::Tensor&) { return torch::ones({obs.size(0), 1}); }
torch::Tensor idle_actions(const torch::Tensor& obs, const torch::Tensor&) { return torch::zeros({obs.size(0), 1}); }

TEST(BodyEval, TheDemonstratorItselfScoresZeroErrorAndAnotherPolicyDoesNot) {
  const auto env = pendulum();
  const auto demos = push_demos(env);
  std::vector<std::string> scored;  // what the task's scorer saw: each row with its own rollout
  const auto result = evaluate_body(env, demos, {0, 1}, torch::zeros({2, 2}), {{"same", push_actions}, {"idle", idle_actions}},
                                    {}, nullptr, [&](const BodyRow& row, const Episode& imitation) {
                                      EXPECT_EQ(imitation.length(), row.steps);
                                      scored.push_back(row.policy + std::to_string(row.episode));
                                    });
  EXPECT_EQ(result.features, env.feature_names());  // recorded by the same task: all of them
  ASSERT_EQ(result.rows.size(), 4u);
  EXPECT_EQ(scored, (std::vector<std::string>{"same0", "same1", "idle0", "idle1"}));
  const int tip_x = 1;  // com_speed, site:tip:x, ...
  EXPECT_EQ(result.features[tip_x], "site:tip:x");
  for (int k = 0; k < 2; ++k) {
    for (double e : result.rows[k].feature_errors) EXPECT_NEAR(e, 0.0, 1e-12);
    EXPECT_EQ(result.rows[k].steps, 30);
    EXPECT_FALSE(result.rows[k].fell);
    EXPECT_EQ(result.rows[k].fall_step, -1);
    EXPECT_GT(result.rows[2 + k].feature_errors[tip_x], 1e-3);
  }
  const std::string table = body_summary_table(result);
  EXPECT_NE(table.find("| same | 2 | 0 | 30 (30) |"), std::string::npos) << table;
  EXPECT_NE(body_rows_csv(result).find("policy,episode,expert_id,fell,fall_step,steps,demo_steps,error_com_speed"), std::string::npos);
}

TEST(BodyEval, FeaturesTheFileLacksAreNotScored) {
  const auto env = pendulum();
  auto demos = push_demos(env);
  // As imported: no features at all.
  demos.header.feature_names.clear();
  for (auto& e : demos.episodes) e.features.clear();
  const auto result = evaluate_body(env, demos, {0}, torch::zeros({1, 2}), {{"same", push_actions}});
  EXPECT_TRUE(result.features.empty());
  ASSERT_EQ(result.rows.size(), 1u);
  EXPECT_TRUE(result.rows[0].feature_errors.empty());
  EXPECT_EQ(result.rows[0].demo_steps, 30);
}

}  // namespace
}  // namespace vaegail::eval
