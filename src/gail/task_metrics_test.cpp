#include "gail/task_metrics.h"

#include <gtest/gtest.h>

namespace vaegail {
namespace {

// Two environments, four steps each: environment 0 ends an episode after step 1 (imitating
// demonstration 0, then 1), environment 1 runs one segment imitating demonstration 0.
struct TwoEnvironments {
  Rollout rollout;
  torch::Tensor demo_of_step = torch::tensor({{0, 0}, {0, 0}, {1, 0}, {1, 0}}, torch::kLong);
  GailDemos demos;
  TwoEnvironments() {
    const auto speed = torch::tensor({{1.f, 0.f}, {1.f, 0.f}, {2.f, 0.f}, {2.f, 4.f}});
    rollout.observations = torch::stack({torch::zeros({4, 2}), speed, torch::ones({4, 2})}, 2);
    rollout.terminated = torch::zeros({4, 2});
    rollout.terminated[1][0] = 1;
    rollout.truncated = torch::zeros({4, 2});
    demos.achieved_speeds = {0.5, 3.0};
  }
};

TEST(GailTaskMetrics, SpeedErrorIsTheMeanOverEpisodeSegments) {
  const TwoEnvironments run;
  const Metrics m = GailTaskMetrics({"rootz", "rootx_vel", "rooty"})(run.rollout, run.demo_of_step, run.demos);
  // Segments: mean speed 1 against 0.5, 2 against 3, 1 against 0.5.
  ASSERT_EQ(m.size(), 1u);
  EXPECT_DOUBLE_EQ(m.at("speed_error"), (0.5 + 1.0 + 0.5) / 3);
}

TEST(GailTaskMetrics, NoneForAnObservationWithoutForwardSpeed) {
  const TwoEnvironments run;
  EXPECT_TRUE(GailTaskMetrics({"a", "b", "c"})(run.rollout, run.demo_of_step, run.demos).empty());
}

}  // namespace
}  // namespace vaegail
