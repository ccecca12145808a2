#include "gail/task_metrics.h"

#include <algorithm>
#include <cmath>

#include "rl/distributed.h"

namespace vaegail {

const std::vector<std::string>& gail_task_metric_columns() {
  static const std::vector<std::string> columns = {"speed_error"};
  return columns;
}

GailTaskMetrics::GailTaskMetrics(const std::vector<std::string>& observation_names) {
  const auto speed = std::find(observation_names.begin(), observation_names.end(), "rootx_vel");
  if (speed != observation_names.end()) speed_index_ = static_cast<int>(speed - observation_names.begin());
}

Metrics GailTaskMetrics::operator()(const Rollout& rollout, const torch::Tensor& demo_of_step,
                                    const GailDemos& demos) const {
  if (speed_index_ < 0) return {};
  const auto speed = rollout.observations.select(2, speed_index_).to(torch::kCPU, torch::kFloat64).contiguous();
  const auto done = ((rollout.terminated + rollout.truncated) > 0).to(torch::kCPU).contiguous();
  const auto s = speed.accessor<double, 2>();
  const auto d = done.accessor<bool, 2>();
  const auto m = demo_of_step.accessor<int64_t, 2>();
  double total = 0, sum = 0, segments = 0;
  int length = 0;
  for (int64_t i = 0; i < speed.size(1); ++i) {
    for (int64_t t = 0; t < speed.size(0); ++t) {
      sum += s[t][i];
      ++length;
      if (!d[t][i] && t + 1 < speed.size(0)) continue;
      total += std::abs(sum / length - demos.achieved_speeds[m[t][i]]);
      ++segments;
      sum = 0;
      length = 0;
    }
  }
  return {{"speed_error", all_sum(total) / all_sum(segments)}};
}

}  // namespace vaegail
