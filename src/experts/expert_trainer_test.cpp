#include "experts/expert_trainer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "data/demos.h"
#include "experts/agent_policy.h"
#include "experts/demo_collection.h"
#include "experts/expert_eval.h"
#include "env/walker.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

ExpertTrainOptions tiny(std::int64_t steps) {
  ExpertTrainOptions o;
  o.total_steps = steps;
  o.num_envs = 2;
  o.steps_per_env = 32;
  o.hidden = {16, 16};
  o.epochs = 2;
  o.minibatches = 2;
  o.checkpoint_every = 1;
  return o;
}

// The last column of every data row.
std::vector<double> last_column(const std::string& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<double> values;
  while (std::getline(in, line)) values.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  return values;
}

int rows(const std::string& csv) {
  std::ifstream in(csv);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n - 1;
}

TEST(ExpertTrainer, ResumesFromItsRunDirectoryAndLoadsForEvaluation) {
  torch::set_num_threads(1);
  const std::string dir = (fs::temp_directory_path() / "vaegail_expert_run").string();
  fs::remove_all(dir);
  ExpertSpec spec{"ctx_test", {-1.0, 1.0}, -1.0, 3};
  train_expert(spec, tiny(128), dir);  // two iterations of 2 x 32 steps
  EXPECT_TRUE(expert_done(dir));
  EXPECT_EQ(expert_steps(dir), 128);
  EXPECT_EQ(rows(dir + "/metrics.csv"), 2);
  // Asking for more steps continues where the run stopped, appending to its metrics.
  train_expert(spec, tiny(256), dir);
  EXPECT_EQ(rows(dir + "/metrics.csv"), 4);
  EXPECT_EQ(expert_steps(dir), 256);
  // Wall-clock keeps counting across the resume.
  const auto seconds = last_column(dir + "/metrics.csv");
  EXPECT_TRUE(std::is_sorted(seconds.begin(), seconds.end()));
  EXPECT_EQ(expert_steps(dir + "/never_started"), 0);
  ExpertSpec other{"other", {1.0}, -1.0, 0};
  EXPECT_THROW(train_expert(other, tiny(64), dir), std::runtime_error);

  const LoadedExpert expert = load_expert(dir);
  EXPECT_EQ(expert.spec.id, "ctx_test");
  EXPECT_EQ(expert.agent->condition_dim(), 1);
  ExpertEvalOptions eval;
  eval.episodes_per_target = 2;
  const ExpertEvaluation result = evaluate_expert(expert, eval);
  ASSERT_EQ(result.targets.size(), 2u);
  EXPECT_EQ(result.targets[0].episodes, 2);

  const std::string demos = dir + "/demos.h5";
  CollectOptions collect;
  collect.episodes_per_expert = 3;
  collect.held_out = {"ctx_test"};
  collect_demos({dir}, demos, collect);
  const DemoSet set = read_demos(demos);
  ASSERT_EQ(set.episodes.size(), 3u);
  EXPECT_EQ(set.episodes[1].context, std::vector<double>{1.0});  // cycles through the targets
  EXPECT_EQ(set.episodes[0].attributes.at("held_out"), 1.0);
  EXPECT_EQ(set.episodes[0].expert_id, "ctx_test");
  fs::remove_all(dir);
  EXPECT_THROW(load_expert(dir), std::runtime_error);
}

// The first column of every data row.
std::vector<int> iterations(const std::string& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<int> values;
  while (std::getline(in, line)) values.push_back(std::stoi(line.substr(0, line.find(','))));
  return values;
}

// What a SIGKILL can leave: metrics rows of iterations after the last checkpoint (one torn), and
// agent.pt written but state.json not yet. The resumed run goes by the state agent.pt holds, redoes
// the lost iterations and logs each iteration once.
TEST(ExpertTrainer, AKilledRunResumesFromItsCheckpointWithOneMetricsRowPerIteration) {
  torch::set_num_threads(1);
  const std::string dir = (fs::temp_directory_path() / "vaegail_expert_killed").string();
  fs::remove_all(dir);
  ExpertSpec spec{"speed_test", {1.0}, -1.0, 5};
  ExpertTrainOptions options = tiny(128);  // two iterations, the checkpoint after the second
  options.checkpoint_every = 2;
  train_expert(spec, options, dir);
  std::ofstream(dir + "/metrics.csv", std::ios::app) << "3,192,1,1,1,0,0,0,0,0,9\n4,25";
  std::ofstream(dir + "/state.json") << R"({"iteration": 1, "steps": 64, "done": false, "seconds": 0})";
  options.total_steps = 192;
  train_expert(spec, options, dir);
  EXPECT_EQ(iterations(dir + "/metrics.csv"), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(expert_steps(dir), 192);
  EXPECT_TRUE(expert_done(dir));
  fs::remove_all(dir);
}

TEST(ExpertTrainer, TrainsTheHumanoidsStylesOnOneHotConditionsAndCollectsThem) {
  torch::set_num_threads(1);
  const std::string dir = (fs::temp_directory_path() / "vaegail_humanoid_expert_run").string();
  fs::remove_all(dir);
  ExpertSpec spec{"styles", {0.0, 3.0}, -1.0, 1, "humanoid", "one_hot"};
  train_expert(spec, tiny(64), dir);
  EXPECT_TRUE(expert_done(dir));
  train_expert(spec, tiny(128), dir);
  EXPECT_EQ(rows(dir + "/metrics.csv"), 2);
  const LoadedExpert expert = load_expert(dir);
  EXPECT_EQ(expert.spec.task, "humanoid");
  EXPECT_EQ(expert.agent->condition_dim(), 2);
  EXPECT_EQ(expert.agent->obs_dim(), 137);
  EXPECT_EQ(expert.agent->act_dim(), 56);
  // No speed to grade it by: its context is a style label (the gait controllers are graded instead).
  EXPECT_THROW(evaluate_expert(expert, ExpertEvalOptions{}), std::invalid_argument);
  // The walker's posture cost has no meaning for another body.
  auto walker_only = tiny(64);
  walker_only.posture_cost = 0.5;
  EXPECT_THROW(train_expert(spec, walker_only, dir + "_posture"), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir + "_posture"));

  const std::string demos = dir + "/demos.h5";
  CollectOptions collect;
  collect.episodes_per_expert = 2;
  collect_demos({dir}, demos, collect);
  const DemoSet set = read_demos(demos);
  EXPECT_EQ(set.header.env_id, "humanoid");
  EXPECT_EQ(set.header.context_names, std::vector<std::string>{"style"});
  ASSERT_EQ(set.episodes.size(), 2u);
  EXPECT_EQ(set.episodes[0].context, std::vector<double>{0.0});
  EXPECT_EQ(set.episodes[1].context, std::vector<double>{3.0});
  fs::remove_all(dir);
}

TEST(ExpertTrainer, PostureCostRoundTripsThroughJsonAndDefaultsToNone) {
  ExpertTrainOptions o;
  o.posture_cost = 0.5;
  const nlohmann::json j = o;
  EXPECT_DOUBLE_EQ(j.get<ExpertTrainOptions>().posture_cost, 0.5);
  // Runs that predate the term (their options.json has no such key) read back without it.
  EXPECT_DOUBLE_EQ(nlohmann::json::object().get<ExpertTrainOptions>().posture_cost, 0.0);
}

TEST(AgentPolicy, StochasticActionsDoNotDependOnBatching) {
  torch::set_num_threads(1);
  ExpertSpec spec{"s", {1.0}, -1.0, 0};
  auto agent = make_expert_agent(spec, tiny(1), 18, 6);
  auto policy = agent_batch_policy(agent, {{}, {}, {}}, true, 9);
  WalkerEnv env;
  env.reset(0);
  const auto obs = env.observation();
  std::vector<float> batch_obs;
  for (int i = 0; i < 3; ++i) batch_obs.insert(batch_obs.end(), obs.begin(), obs.end());
  const int episodes[3] = {0, 1, 2}, steps[3] = {0, 0, 0};
  std::vector<float> together(18), alone(6);
  policy(3, batch_obs.data(), episodes, steps, together.data());
  auto fresh = agent_batch_policy(agent, {{}, {}, {}}, true, 9);
  fresh(1, obs.data(), &episodes[2], steps, alone.data());
  EXPECT_EQ(std::vector<float>(together.begin() + 12, together.end()), alone);
  EXPECT_NE(std::vector<float>(together.begin(), together.begin() + 6), alone);
}

}  // namespace
}  // namespace vaegail
