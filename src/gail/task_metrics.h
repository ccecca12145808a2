// The metrics.csv columns of a GAIL run that only some tasks have, apart from the generic
// trainer (diverse_gail.h), which writes them beside its own: the walker's speed error.
#pragma once

#include <torch/torch.h>

#include <string>
#include <vector>

#include "gail/gail_demos.h"
#include "rl/rollout.h"
#include "util/csv_log.h"

namespace vaegail {

// The columns a task may fill. Every run's metrics.csv has them, NaN where its task fills none,
// so that files keep the columns they had (a resumed run appends to its file).
const std::vector<std::string>& gail_task_metric_columns();

class GailTaskMetrics {
 public:
  // The task's metrics, found by the environment's observation names.
  explicit GailTaskMetrics(const std::vector<std::string>& observation_names);

  // One iteration's metrics by column name, from its rollout and the demonstration each step
  // [T, N] imitated: for an observation with a forward speed (rootx_vel, the walker's)
  // speed_error, the mean over the run's episode segments of |mean forward speed − the
  // demonstration's achieved speed|; nothing otherwise. Under mpirun every rank calls it (it
  // sums over the ranks).
  Metrics operator()(const Rollout& rollout, const torch::Tensor& demo_of_step, const GailDemos& demos) const;

 private:
  int speed_index_ = -1;  // rootx_vel's, -1 if the observation has none
};

}  // namespace vaegail
