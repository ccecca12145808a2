#include "data/demo_stats.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vaegail {
namespace {

TEST(DemoStats, MomentsMatchDirectComputation) {
  const Moments m = moments({1, 2, 3, 4});
  EXPECT_EQ(m.count, 4);
  EXPECT_DOUBLE_EQ(m.mean, 2.5);
  EXPECT_DOUBLE_EQ(m.std, std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(m.min, 1);
  EXPECT_DOUBLE_EQ(m.max, 4);
}

TEST(DemoStats, CountsContextsAndAveragesFeaturesOverReachedStates) {
  DemoSet set;
  set.header.feature_names = {"speed"};
  set.header.context_names = {"target_speed"};
  for (int i = 0; i < 3; ++i) {
    Episode e;
    e.rewards = {0, 0};
    e.terminations = {0, static_cast<std::uint8_t>(i == 2)};
    e.features = {100.0, 1.0 + i, 3.0 + i};  // the initial state's value is not averaged
    e.context = {i < 2 ? 1.0 : 3.0};
    e.expert_id = i < 2 ? "a" : "b";
    set.episodes.push_back(e);
  }
  const DemoSummary s = summarize(set);
  EXPECT_EQ(s.episodes, 3);
  EXPECT_EQ(s.steps, 6);
  EXPECT_EQ(s.terminated_episodes, 1);
  EXPECT_EQ((s.episodes_per_context.at({1.0})), 2);
  EXPECT_EQ((s.episodes_per_context.at({3.0})), 1);
  EXPECT_EQ(s.episodes_per_expert.size(), 2u);
  EXPECT_DOUBLE_EQ(s.episode_mean[0].mean, 3.0);  // means 2, 3, 4
  EXPECT_DOUBLE_EQ(s.per_step[0].max, 5.0);
  EXPECT_NE(format_summary(set, s).find("target_speed"), std::string::npos);
}

}  // namespace
}  // namespace vaegail
