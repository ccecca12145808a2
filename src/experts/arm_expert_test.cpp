#include "experts/arm_expert.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "data/demos.h"
#include "env/arm.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

std::string fresh_dir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/" + name;
  fs::remove_all(dir);
  return dir;
}

ArmExpertOptions tiny_options() {
  ArmExpertOptions o;
  o.total_steps = 300;
  o.eval_every = 100;
  o.ddpg.actor_hidden = {16};
  o.ddpg.critic_hidden = {16};
  o.ddpg.warmup_steps = 100;
  return o;
}

TEST(ArmExperts, SpecsAreReproducibleDistinctAndInTheWorkspace) {
  const auto a = arm_expert_specs(60, 7), b = arm_expert_specs(60, 7), c = arm_expert_specs(60, 8);
  ASSERT_EQ(a.size(), 60u);
  EXPECT_EQ(a[0].id, "reach_00");
  EXPECT_EQ(a[59].id, "reach_59");
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].target, b[i].target);
    EXPECT_NE(a[i].target, c[i].target);
    if (i) EXPECT_NE(a[i].target, a[i - 1].target);
    if (i) EXPECT_NE(a[i].seed, a[i - 1].seed);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(a[i].target[k], ArmEnv::kTargetLow[k]);
      EXPECT_LE(a[i].target[k], ArmEnv::kTargetHigh[k]);
    }
  }
}

TEST(ArmExperts, OptionsSurviveJson) {
  ArmExpertOptions o = tiny_options();
  o.ddpg.tau = 0.01;
  o.posture_cost = 0.1;
  const ArmExpertOptions back = nlohmann::json(o).get<ArmExpertOptions>();
  EXPECT_EQ(back.total_steps, 300);
  EXPECT_DOUBLE_EQ(back.posture_cost, 0.1);
  EXPECT_DOUBLE_EQ(nlohmann::json::object().get<ArmExpertOptions>().posture_cost, 0.0);  // runs that predate it
  EXPECT_EQ(back.ddpg.actor_hidden, std::vector<int>{16});
  EXPECT_DOUBLE_EQ(back.ddpg.tau, 0.01);
  EXPECT_THROW(nlohmann::json({{"id", "x"}, {"target", {1.0, 2.0}}, {"seed", 1}}).get<ArmExpertSpec>(),
               std::invalid_argument);
}

TEST(ArmExperts, ATrainedRunIsSkippedLoadsAndDemonstratesDistinctEpisodesTowardsItsTarget) {
  const auto spec = arm_expert_specs(1, 3)[0];
  const std::string dir = fresh_dir("arm_expert_run");
  const ArmExpertResult result = train_arm_expert(spec, tiny_options(), dir);
  ASSERT_TRUE(arm_expert_done(dir));
  EXPECT_GT(result.best_return, 0.0);
  EXPECT_GE(result.path_ratio, 1.0);  // no path is shorter than the straight line
  // Finished: a second call trains nothing and returns the stored result.
  const auto again = train_arm_expert(spec, tiny_options(), dir, [](std::int64_t) { FAIL() << "retrained"; });
  EXPECT_DOUBLE_EQ(again.best_return, result.best_return);

  const LoadedArmExpert loaded = load_arm_expert(dir);
  EXPECT_EQ(loaded.spec.target, spec.target);
  EXPECT_DOUBLE_EQ(loaded.result.final_distance, result.final_distance);
  EXPECT_DOUBLE_EQ(loaded.result.path_ratio, result.path_ratio);

  const std::string demos = dir + "/demos.h5";
  ArmCollectOptions collect;
  collect.episodes_per_expert = 3;
  collect.held_out = {spec.id};
  collect_arm_demos({dir}, demos, collect);
  const DemoSet set = read_demos(demos);
  ASSERT_EQ(set.episodes.size(), 3u);
  EXPECT_EQ(set.header.env_id, "arm");
  for (const auto& e : set.episodes) {
    EXPECT_EQ(e.expert_id, spec.id);
    EXPECT_EQ(e.context, spec.target);
    EXPECT_EQ(e.length(), 50);
    EXPECT_EQ(e.attributes.at("held_out"), 1.0);
    // The stored final distance is the last step's grip-to-target feature.
    EXPECT_DOUBLE_EQ(e.attributes.at("final_distance"), e.features[50 * 4 + 3]);
  }
  EXPECT_EQ(set.episodes[0].observations[0], set.episodes[1].observations[0]);  // same home pose
  EXPECT_NE(set.episodes[0].actions, set.episodes[1].actions);                   // exploration noise
}

TEST(ArmExperts, LoadingSomethingElseNamesTheMissingFile) {
  const std::string dir = fresh_dir("arm_expert_empty");
  fs::create_directories(dir);
  try {
    load_arm_expert(dir);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("spec.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace vaegail
