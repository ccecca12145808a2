#include "eval/arm_eval.h"

#include <gtest/gtest.h>

#include "data/record.h"
#include "env/arm.h"

namespace vaegail::eval {
namespace {

const std::vector<float> kPoseA = {0.3f, 0.8f, 0.4f, 0, 0, 0, 0, 0, 0};
const std::vector<float> kPoseB = {-0.5f, 0.5f, 0.9f, 0, 0, 0, 0, 0, 0};

// Two demonstrations: servoing to pose A, then to pose B.
DemoSet two_reaches(const ArmEnv& env) {
  DemoSet demos{"two", header_for(env), {}};
  for (const auto* pose : {&kPoseA, &kPoseB}) {
    RecordRequest r;
    r.seeds = {0};
    r.expert_id = pose == &kPoseA ? "a" : "b";
    const BatchPolicy hold = [pose](int n, const float*, const int*, const int*, float* actions) {
      for (int b = 0; b < n; ++b) std::copy(pose->begin(), pose->end(), actions + b * 9);
    };
    auto episodes = record_episodes(env, r, hold);
    episodes[0].attributes["held_out"] = pose == &kPoseB ? 1.0 : 0.0;
    demos.episodes.push_back(episodes[0]);
  }
  return demos;
}

torch::Tensor as_z(const std::vector<float>& pose) { return torch::tensor(pose).unsqueeze(0); }

TEST(ArmEval, SegmentCoordinatesByHand) {
  const auto [along, off] = segment_coordinates({0, 0, 0}, {2, 0, 0}, {1, 1, 0});
  EXPECT_DOUBLE_EQ(along, 0.5);
  EXPECT_DOUBLE_EQ(off, 1.0);
  const auto [beyond, on_line] = segment_coordinates({1, 1, 1}, {1, 1, 3}, {1, 1, 6});
  EXPECT_DOUBLE_EQ(beyond, 2.5);
  EXPECT_DOUBLE_EQ(on_line, 0.0);
  EXPECT_THROW(segment_coordinates({1, 2, 3}, {1, 2, 3}, {0, 0, 0}), std::invalid_argument);
}

TEST(ArmEval, DistanceSummaryMeanMedianAndNinetiethPercentile) {
  const auto s = summarize_distances({10, 1, 9, 2, 8, 3, 7, 4, 6, 5});
  EXPECT_EQ(s.n, 10);
  EXPECT_DOUBLE_EQ(s.mean, 5.5);
  EXPECT_DOUBLE_EQ(s.median, 5.5);
  EXPECT_NEAR(s.p90, 9.1, 1e-12);  // rank 8.1 between 9 and 10
  EXPECT_EQ(summarize_distances({}).n, 0);
}

TEST(ArmEval, MonotoneAllowsOnlyTheToleratedStepBack) {
  InterpolationPair p;
  p.along = {0.0, 0.3, 0.2, 0.7, 1.0};
  EXPECT_FALSE(p.monotone(0.0));
  EXPECT_TRUE(p.monotone(0.15));
  p.along = {0.0, 0.25, 0.5, 0.75, 1.0};
  EXPECT_TRUE(p.monotone(0.0));
}

TEST(ArmEval, MonotonePairsCountedBySegmentLength) {
  auto pair = [](double length, bool monotone) {
    InterpolationPair p;
    p.demo_end_b = {length, 0, 0};
    p.along = monotone ? std::vector<double>{0, 1} : std::vector<double>{1, 0};
    return p;
  };
  const std::vector<InterpolationPair> pairs{pair(0.1, false), pair(0.2, true), pair(0.3, false),
                                             pair(0.5, true), pair(0.9, true)};
  const auto bins = monotone_by_segment_length(pairs, 0.0, {0.2, 0.4});
  ASSERT_EQ(bins.size(), 3u);
  EXPECT_EQ(bins[0], (std::pair<int, int>{0, 1}));  // [0, 0.2)
  EXPECT_EQ(bins[1], (std::pair<int, int>{1, 2}));  // [0.2, 0.4): 0.2 belongs here
  EXPECT_EQ(bins[2], (std::pair<int, int>{2, 2}));  // 0.4 and longer
  EXPECT_THROW(monotone_by_segment_length(pairs, 0.0, {0.4, 0.2}), std::invalid_argument);
}

TEST(ArmEval, ImitationWithTheDemonstratorsCommandEndsWhereTheDemonstrationDid) {
  const ArmEnv env;
  const DemoSet demos = two_reaches(env);
  const auto rows = imitate_reaches(env, demos, {0, 1}, torch::cat({as_z(kPoseA), as_z(kPoseA)}), kHoldZAsCommand);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].demo_path.size(), 51u);
  EXPECT_NEAR(rows[0].final_distance(), 0.0, 1e-9);  // same commands, same physics
  EXPECT_FALSE(rows[0].held_out);
  EXPECT_TRUE(rows[1].held_out);
  EXPECT_GT(rows[1].final_distance(), 0.2);  // pose A's end is far from pose B's
  const std::string csv = reach_rows_csv(rows);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  // The figure's data: per row a solid demonstration and a dashed imitation path, one colour group.
  const std::string paths = reach_paths_csv(rows);
  EXPECT_EQ(std::count(paths.begin(), paths.end(), '\n'), 1 + 4 * 51);
  EXPECT_EQ(paths.rfind("path,group,label,style,x,y\n0,0,demonstration,solid,", 0), 0u);
  EXPECT_NE(paths.find("\n3,1,,dashed,"), std::string::npos);
}

TEST(ArmEval, InterpolationEndsAtTheTwoDemonstrationsAndMovesBetweenThem) {
  const ArmEnv env;
  const DemoSet demos = two_reaches(env);
  const auto pairs = interpolate_reaches(env, demos, {{0, 1}}, as_z(kPoseA), as_z(kPoseB),
                                         {0.0, 0.25, 0.5, 0.75, 1.0}, kHoldZAsCommand);
  ASSERT_EQ(pairs.size(), 1u);
  const auto& p = pairs[0];
  EXPECT_NEAR(p.along.front(), 0.0, 1e-9);
  EXPECT_NEAR(p.along.back(), 1.0, 1e-9);
  EXPECT_NEAR(p.off_line.front(), 0.0, 1e-9);
  EXPECT_NEAR(p.off_line.back(), 0.0, 1e-9);
  // Joint-space blending moves the hand along an arc: monotone, off the chord but not far.
  EXPECT_TRUE(p.monotone(0.0));
  for (double off : p.off_line) EXPECT_LT(off, 0.25);
  EXPECT_EQ(p.paths.size(), 5u);
  const std::string csv = interpolation_csv(pairs);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 6);
  // The figure's data: both demonstrations (groups 0 and 1), then one dashed path per alpha.
  const std::string paths = interpolation_paths_csv(p, demos);
  EXPECT_EQ(std::count(paths.begin(), paths.end(), '\n'), 1 + 7 * 51);
  EXPECT_NE(paths.find("\n1,1,demonstration b,solid,"), std::string::npos);
  EXPECT_NE(paths.find("\n4,0.50,alpha 0.50,dashed,"), std::string::npos);
}

}  // namespace
}  // namespace vaegail::eval
