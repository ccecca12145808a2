// The evaluation of any body (`vaegail eval body`), for tasks without an evaluation of their
// own: each policy imitates demonstrations from their initial states (the walker evaluation's
// rollouts, walker_eval.h), and each imitation is scored against its demonstration by
//   fell             the rollout terminated, or its `fallen` feature (when the task has one) rose
//   steps            how long it ran
//   feature errors   per feature both the task and the file have: the mean over steps
//                    t = 1..min(T_demo, T_imitation) of |f_imitation(t) - f_demo(t)|
// Demonstrations imported without features (data import) score falls and steps only.
#pragma once

#include <torch/torch.h>

#include <functional>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "eval/walker_eval.h"

namespace vaegail::eval {

struct BodyRow {
  std::string policy, expert_id;
  int64_t episode = 0;
  bool fell = false;
  int fall_step = -1;  // the first control step whose state had fallen, or the terminating one; -1: none
  int steps = 0, demo_steps = 0;
  std::vector<double> feature_errors;  // one per BodyEval::features
};

struct BodyEval {
  std::vector<std::string> features;  // scored: in the task's and the file's feature lists
  std::vector<BodyRow> rows;
};

// Features of `env` that the demonstrations also record, in the environment's order.
std::vector<std::string> shared_features(const Env& env, const DemoHeader& header);

// Per-feature mean |imitation - demonstration| over the steps both ran (0 when either has none).
std::vector<double> feature_errors(const Episode& demo, const DemoHeader& header, const Episode& imitation,
                                   const Env& env, const std::vector<std::string>& features);

// A task's own measure of an imitation (the humanoid's style): called with each row and its
// rollout, in row order.
using ImitationScorer = std::function<void(const BodyRow& row, const Episode& imitation)>;

// Every policy imitates every listed episode; z [episodes.size(), Z] holds their embeddings.
BodyEval evaluate_body(const Env& prototype, const DemoSet& demos, const std::vector<int64_t>& episodes,
                       const torch::Tensor& z, const std::vector<NamedPolicy>& policies,
                       const vae::ImitationOptions& options = {}, Progress* progress = nullptr,
                       const ImitationScorer& score = nullptr);

// One row per imitation: policy, episode, expert_id, fell, fall_step, steps, demo_steps, error_<feature>...
std::string body_rows_csv(const BodyEval& eval);
// A Markdown table, one row per policy: imitations, fall rate, mean steps, and the mean error of
// each scored feature.
std::string body_summary_table(const BodyEval& eval);

}  // namespace vaegail::eval
