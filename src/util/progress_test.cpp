#include "util/progress.h"

#include <gtest/gtest.h>

#include <stdexcept>

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

// A job ended by an error draws no final bar claiming it done: the error's line stands alone.
TEST(ProgressTest, AnErrorEndsTheJobWithoutItsFinalBar) {
  ::testing::internal::CaptureStderr();  // not a terminal: only the final bar would be drawn here
  try {
    Progress progress("job", 3);
    progress.set(1);
    throw std::runtime_error("disk full");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  ::testing::internal::CaptureStderr();
  {
    Progress progress("job", 3);
    progress.set(3);
  }
  EXPECT_NE(::testing::internal::GetCapturedStderr().find("job [########################] 3/3"), std::string::npos);
}

}  // namespace
}  // namespace vaegail
