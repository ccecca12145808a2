#include "experts/humanoid_gait.h"

#include <gtest/gtest.h>

#include <cmath>

#include "env/humanoid.h"

namespace vaegail {
namespace {

// A three-step episode whose features are zero but for the named columns, set per state t = 0..3.
Episode hand_made(const std::vector<std::string>& names, const std::map<std::string, std::array<double, 4>>& set) {
  Episode e;
  e.rewards.assign(3, 0.0);
  e.features.assign(4 * names.size(), 0.0);
  for (const auto& [name, values] : set) {
    const size_t f = std::find(names.begin(), names.end(), name) - names.begin();
    for (int t = 0; t < 4; ++t) e.features[t * names.size() + f] = values[t];
  }
  return e;
}

TEST(GaitSignature, MatchesHandComputedStatistics) {
  const auto names = HumanoidEnv().feature_names();
  const Episode e = hand_made(names, {{"forward_speed", {9, 1, 2, 3}},  // state 0 is before any action: left out
                                      {"heading", {3.1, -3.1, -3.0, -3.2}},
                                      {"root_height", {0, 0.9, 0.8, 0.7}},
                                      {"head_x", {0, 0.1, 0.1, 0.1}},
                                      {"lhand_z", {0, -0.1, -0.1, -0.1}},
                                      {"rhand_z", {0, -0.3, -0.3, -0.3}},
                                      {"lhand_y", {0, 0.2, 0.2, 0.2}},
                                      {"rhand_y", {0, -0.4, -0.4, -0.4}},
                                      {"lfoot_y", {0, 0.1, 0.1, 0.1}},
                                      {"rfoot_y", {0, -0.05, -0.05, -0.05}},
                                      {"lhand_x", {5, 0.1, 0.3, 0.1}}});
  const GaitSignature s = gait_signature(e, names, 0.03);
  EXPECT_NEAR(s[0], 2.0, 1e-12);
  // Across +-pi the heading turned 2 pi - 6.2 rad, then 0.1 and 0.2 rad.
  EXPECT_NEAR(s[1], ((2 * M_PI - 6.2) + 0.1 + 0.2) / 3 / 0.03, 1e-9);
  EXPECT_NEAR(s[2], 0.8, 1e-12);
  EXPECT_NEAR(s[3], 0.1, 1e-12);
  EXPECT_NEAR(s[4], -0.2, 1e-12);
  EXPECT_NEAR(s[5], 0.3, 1e-12);
  EXPECT_NEAR(s[6], 0.075, 1e-12);
  EXPECT_NEAR(s[7], std::sqrt(2.0) * 0.2 / 3, 1e-12);  // {0.1, 0.3, 0.1}: deviations -1/15, 2/15, -1/15
  EXPECT_THROW(gait_signature(e, {"forward_speed"}, 0.03), std::invalid_argument);
}

TEST(GaitSignature, AfterAStepTakesOnlyTheStatesThatFollowIt) {
  const auto names = HumanoidEnv().feature_names();
  const Episode e = hand_made(names, {{"forward_speed", {9, 1, 2, 4}}, {"lhand_x", {0, 5, 0.1, 0.3}}});
  const GaitSignature s = gait_signature(e, names, 0.03, 1);
  EXPECT_NEAR(s[0], 3.0, 1e-12);
  EXPECT_NEAR(s[7], 0.1, 1e-12);  // {0.1, 0.3}
  EXPECT_THROW(gait_signature(e, names, 0.03, 3), std::invalid_argument);
}

// Two styles that both start from standing (speed 0, hands down) and differ afterwards: the
// demonstrations' second halves walk at 1.2 m/s with low hands ("train/walk") or at 0.6 m/s with
// raised hands ("train/chicken").
DemoSet two_style_demos() {
  DemoSet demos;
  demos.path = "two_styles.h5";
  demos.header.feature_names = HumanoidEnv().feature_names();
  const auto& names = demos.header.feature_names;
  for (int i = 0; i < 6; ++i) {
    const bool walk = i % 2 == 0;
    const double wobble = 0.01 * i;
    Episode e = hand_made(names, {{"forward_speed", {0, 0, walk ? 1.2 + wobble : 0.6 + wobble, walk ? 1.2 : 0.6}},
                                  {"lhand_z", {-0.3, -0.3, walk ? -0.3 : 0.1, walk ? -0.3 : 0.1}},
                                  {"rhand_z", {-0.3, -0.3, walk ? -0.3 : 0.1, walk ? -0.3 : 0.1}}});
    e.expert_id = walk ? "train/walk" : "train/chicken";
    demos.episodes.push_back(e);
  }
  return demos;
}

TEST(StyleClassifier, NamesAStretchByTheDemonstrationsSameStretch) {
  const DemoSet demos = two_style_demos();
  const StyleLabels labels = style_labels(demos);
  EXPECT_EQ(labels.names, (std::vector<std::string>{"train/walk", "train/chicken"}));
  EXPECT_EQ(labels.of_episode, (std::vector<int>{0, 1, 0, 1, 0, 1}));
  const auto& names = demos.header.feature_names;
  // A rollout that starts like either and then walks at 1.1 m/s with its hands up a little.
  const Episode rollout =
      hand_made(names, {{"forward_speed", {0, 0, 1.1, 1.1}}, {"lhand_z", {-0.3, -0.3, -0.2, -0.2}},
                        {"rhand_z", {-0.3, -0.3, -0.2, -0.2}}});
  const StyleClassifier after_one(demos, 0.03, 1);
  EXPECT_EQ(after_one.name(gait_signature(rollout, names, 0.03, 1)), "train/walk");
  const Episode chicken = hand_made(names, {{"forward_speed", {0, 0, 0.7, 0.5}}, {"lhand_z", {0, 0, 0.2, 0.0}},
                                            {"rhand_z", {0, 0, 0.1, 0.1}}});
  EXPECT_EQ(after_one.name(gait_signature(chicken, names, 0.03, 1)), "train/chicken");
  EXPECT_EQ(StyleClassifier(demos, 0.03).name(gait_signature(demos.episodes[3], names, 0.03)), "train/chicken");
  EXPECT_THROW(StyleClassifier(demos, 0.03, 3), std::invalid_argument);  // no demonstration runs past step 3
}

TEST(NearestCentroid, NamesSeparatedStylesAndCountsItsMistakes) {
  // Two styles apart in speed only (the other statistics constant), the speed's spread
  // standardised away; a third row of style 1 sits nearer style 0's centroid.
  std::vector<GaitSignature> rows;
  std::vector<int> labels;
  for (int i = 0; i < 6; ++i) {
    GaitSignature r{};
    r[0] = (i % 2 ? 100.0 : 0.0) + i;
    rows.push_back(r);
    labels.push_back(i % 2 ? 7 : 3);
  }
  const Confusion all_right = split_half_confusion(rows, labels);
  // Of each style's three rows the first and third are fitted, the second named.
  EXPECT_EQ(all_right.at(3).at(3), 1);
  EXPECT_EQ(all_right.at(7).at(7), 1);
  EXPECT_EQ(all_right.size(), 2u);
  EXPECT_DOUBLE_EQ(accuracy(all_right), 1.0);
  NearestCentroid c;
  c.fit(rows, labels);
  GaitSignature near_three{};
  near_three[0] = 30;
  EXPECT_EQ(c.predict(near_three), 3);
  near_three[0] = 70;
  EXPECT_EQ(c.predict(near_three), 7);
  const Confusion mixed = {{3, {{3, 3}, {7, 1}}}, {7, {{7, 4}}}};
  EXPECT_DOUBLE_EQ(accuracy(mixed), 7.0 / 8.0);
  EXPECT_THROW(c.fit({}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace vaegail
