#include "util/progress.h"

#include <gtest/gtest.h>

namespace vaegail {
namespace {

TEST(ProgressTest, EtaIsTheWorkLeftOverTheRate) {
  EXPECT_DOUBLE_EQ(Progress::eta_seconds(100, 4.0, -1), 25.0);
  EXPECT_DOUBLE_EQ(Progress::eta_seconds(100, 0.0, -1), -1.0);
}

TEST(ProgressTest, ATimeBudgetCapsTheEta) {
  // 29,856 iterations at 0.7 it/s would take 11.8 hours; a 4-minute budget with 3.5 spent ends in 30 s.
  EXPECT_DOUBLE_EQ(Progress::eta_seconds(29856, 0.7, 30.0), 30.0);
  EXPECT_DOUBLE_EQ(Progress::eta_seconds(10, 1.0, 30.0), 10.0);  // the work ends first
  EXPECT_DOUBLE_EQ(Progress::eta_seconds(10, 0.0, 30.0), 30.0);  // no rate yet: the budget bounds it
}

TEST(ProgressTest, FormatsDurations) {
  EXPECT_EQ(Progress::format_duration(65), "01:05");
  EXPECT_EQ(Progress::format_duration(3725), "1:02:05");
  EXPECT_EQ(Progress::format_duration(-1), "--:--");
}

}  // namespace
}  // namespace vaegail
