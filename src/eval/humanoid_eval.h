// The humanoid's evaluation, the paper's Figure 5 right (section 4.3): how often each policy's
// imitation of a demonstration falls before the episode's end, for the training controllers'
// demonstrations and, one-shot, for the evaluation controllers' (encoded by the VAE trained on
// the training set, imitated from the demonstration's initial state). The rollouts are
// body_eval.h's. Beside each fall, whether the imitation keeps the demonstration's style:
// experts/humanoid_gait.h's StyleClassifier, fitted on the whole episodes of the demonstration's
// own file, names the imitation's style from its gait signature. Only imitations that ran to the
// episode's end are named: a fallen body's statistics describe a fall, not a gait.
#pragma once

#include <torch/torch.h>

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "eval/walker_eval.h"
#include "vae/imitation.h"

namespace vaegail::eval {

struct HumanoidRow {
  std::string set;            // the demonstrations' file: "train" or "eval"
  std::string policy, style;  // style: the demonstration's (its expert id, "train/walk")
  int64_t episode = 0;
  bool fell = false;
  int fall_step = -1;                  // the control step of the fall; -1: stayed up to the end
  double fall_seconds = std::nan("");  // fall_step x the control step
  int steps = 0, demo_steps = 0;
  std::string named_style;  // the classifier's name for the imitation; "" when it fell
  bool kept_style() const { return !fell && named_style == style; }
};

// Every policy imitates every listed episode of `demos` (the file of set `set`); z
// [episodes.size(), Z] holds their embeddings. Throws when the file's styles cannot be classified.
std::vector<HumanoidRow> evaluate_humanoid(const Env& prototype, const DemoSet& demos, const std::string& set,
                                           const std::vector<int64_t>& episodes, const torch::Tensor& z,
                                           const std::vector<NamedPolicy>& policies,
                                           const vae::ImitationOptions& options = {}, Progress* progress = nullptr);

struct HumanoidSummary {
  std::string set, policy, style;  // style "all": the set's every controller
  int imitations = 0, falls = 0, kept_style = 0;
  double mean_fall_seconds = std::nan("");  // over the falls
  int stayed_up() const { return imitations - falls; }
  double fall_rate() const { return imitations ? static_cast<double>(falls) / imitations : std::nan(""); }
  // Of the imitations that stayed up; NaN when none did.
  double kept_style_rate() const { return stayed_up() ? static_cast<double>(kept_style) / stayed_up() : std::nan(""); }
};

// Per set, controller (style) and policy, the sets, controllers and policies in order of
// appearance; each set's controllers followed by its "all" rows.
std::vector<HumanoidSummary> summarize_humanoid(const std::vector<HumanoidRow>& rows);

// One row per imitation: set, policy, episode, style, fell, fall_step, fall_seconds, steps,
// demo_steps, named_style, kept_style.
std::string humanoid_rows_csv(const std::vector<HumanoidRow>& rows);
// A Markdown table of the summaries: imitations, falls (%), mean time of a fall, stayed up, kept
// the style (of those that stayed up).
std::string humanoid_table(const std::vector<HumanoidSummary>& summaries);
// The summaries as JSON: {"summaries": [{set, style, policy, imitations, falls, fall_rate, ...}]}.
nlohmann::json humanoid_json(const std::vector<HumanoidSummary>& summaries);
// The bar chart's data (scripts/plot/bars.py): group (controller: its expert id, which names its
// set, "eval/drunk"; else "SET: id"), series (policy), value (falls, % of the imitations), one row
// per controller and policy.
std::string humanoid_falls_csv(const std::vector<HumanoidSummary>& summaries);

}  // namespace vaegail::eval
