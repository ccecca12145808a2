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

}  // namespace
}  // namespace vaegail
