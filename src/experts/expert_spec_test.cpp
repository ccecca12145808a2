#include "experts/expert_spec.h"

#include <gtest/gtest.h>

#include <set>

namespace vaegail {
namespace {

TEST(ExpertSpec, PaperGridCoversEveryGroupLogStdAndSeed) {
  const auto specs = expand(paper_walker_grid());
  EXPECT_EQ(specs.size(), 6u * 4u * 3u);
  std::set<std::string> ids;
  int conditioned = 0;
  for (const auto& s : specs) {
    ids.insert(s.id);
    conditioned += s.conditioned();
  }
  EXPECT_EQ(ids.size(), specs.size());
  EXPECT_EQ(conditioned, 2 * 4 * 3);
  EXPECT_EQ(expand(small_walker_grid()).size(), 12u);
}

TEST(ExpertSpec, JsonRoundTrip) {
  const ExpertSpec s = expand(paper_walker_grid())[40];
  const ExpertSpec back = nlohmann::json(s).get<ExpertSpec>();
  EXPECT_EQ(back.id, s.id);
  EXPECT_EQ(back.targets, s.targets);
  EXPECT_EQ(back.init_log_std, s.init_log_std);
  EXPECT_EQ(back.seed, s.seed);
  const ExpertGrid g = nlohmann::json(paper_walker_grid()).get<ExpertGrid>();
  EXPECT_EQ(expand(g).size(), 72u);
}

TEST(ExpertSpec, AFirstSeedContinuesAnEarlierGridWithoutReusingItsIds) {
  ExpertGrid earlier{{{-1}, {1}}, {-1, 0}, 4};
  ExpertGrid later = earlier;
  later.first_seed = 4;
  std::set<std::string> ids;
  for (const auto& s : expand(earlier)) ids.insert(s.id);
  for (const auto& s : expand(later)) {
    EXPECT_GE(s.seed, 4u);
    EXPECT_LT(s.seed, 8u);
    EXPECT_TRUE(ids.insert(s.id).second) << s.id;
  }
  EXPECT_EQ(ids.size(), 32u);
  const auto back = nlohmann::json::parse(R"({"groups": [[0]], "init_log_stds": [-1], "seeds": 2, "first_seed": 6})")
                        .get<ExpertGrid>();
  EXPECT_EQ(expand(back).back().id, "speed0_logstd-1_seed7");
  EXPECT_EQ(nlohmann::json(later).get<ExpertGrid>().first_seed, 4);
}

TEST(ExpertSpec, OneHotConditionsNameTheTargetsPosition) {
  const auto grid = nlohmann::json::parse(R"({"groups": [[0, 3, 1], [2]], "init_log_stds": [-1], "seeds": 1,
                                               "task": "humanoid", "condition": "one_hot"})").get<ExpertGrid>();
  const auto specs = expand(grid);
  ASSERT_EQ(specs.size(), 2u);
  const ExpertSpec& styles = specs[0];
  EXPECT_EQ(styles.id, "humanoid_ctx0_3_1_logstd-1_seed0");
  EXPECT_EQ(styles.task, "humanoid");
  EXPECT_EQ(styles.condition_dim(), 3);
  EXPECT_EQ(styles.condition_for(3), (std::vector<float>{0, 1, 0}));
  EXPECT_EQ(styles.condition_for(1), (std::vector<float>{0, 0, 1}));
  EXPECT_THROW(styles.condition_for(2), std::invalid_argument);
  EXPECT_EQ(specs[1].condition_dim(), 0);  // a single style needs no condition
  EXPECT_TRUE(specs[1].condition_for(2).empty());
  const ExpertSpec back = nlohmann::json(styles).get<ExpertSpec>();
  EXPECT_EQ(back.task, "humanoid");
  EXPECT_EQ(back.condition_for(1), styles.condition_for(1));

  // The walker's experts keep the value itself, and spec files from before tasks read as theirs.
  const ExpertSpec walker = expand(paper_walker_grid())[50];
  ASSERT_TRUE(walker.conditioned());
  EXPECT_EQ(walker.condition_for(-1), std::vector<float>{-1});
  const auto old = nlohmann::json::parse(R"({"id": "a", "targets": [0, 1], "init_log_std": -1, "seed": 0})")
                       .get<ExpertSpec>();
  EXPECT_EQ(old.task, "walker");
  EXPECT_EQ(old.condition_dim(), 1);
  EXPECT_THROW(nlohmann::json::parse(R"({"groups": [[0]], "init_log_stds": [-1], "seeds": 1, "condition": "bits"})")
                   .get<ExpertGrid>(), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail
