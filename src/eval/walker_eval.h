// The paper's walker measurement (section 4.2, Figure 4 bottom right): take some
// demonstrations of every expert, encode each, imitate it from its own initial state, and
// compare the imitation's average speed with the demonstration's. Policies that take no z
// (plain GAIL, BC) are rolled out from the same starts, so their speed distribution can be
// set against the demonstrations' (mode collapse shows as one narrow peak).
#pragma once

#include <torch/torch.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "vae/imitation.h"

namespace vaegail::eval {

struct NamedPolicy {
  std::string name;  // "vae", "diverse_gail", "plain_gail", "bc"
  vae::LatentPolicy policy;  // policies without a latent ignore z
};

// The first `per_expert` episodes of each expert id, in file order (experts in order of
// first appearance).
std::vector<int64_t> episodes_per_expert(const DemoSet& demos, int per_expert);

struct ImitationRow {
  std::string policy, expert_id;
  int64_t episode = 0;
  double target = 0;  // the episode's context (target speed)
  bool held_out = false;
  double demo_speed = 0, achieved_speed = 0;
  bool fell = false;
  double abs_difference() const { return std::abs(demo_speed - achieved_speed); }
};

// Every policy imitates every episode; z [episodes.size(), Z] holds their embeddings.
std::vector<ImitationRow> imitate_with_policies(const Env& prototype, const DemoSet& demos,
                                                const std::vector<int64_t>& episodes, const torch::Tensor& z,
                                                const std::vector<NamedPolicy>& policies,
                                                const vae::ImitationOptions& options = {},
                                                Progress* progress = nullptr);

struct ImitationSummary {
  std::string policy;
  bool held_out = false;
  double target = std::nan("");  // summaries by target only
  int demonstrations = 0;
  double median_abs_difference = 0, mean_abs_difference = 0, fall_rate = 0;
  double median_achieved_speed = 0;
};

// One summary per (policy, held_out) present, or with `by_target` per (policy, held_out,
// target), in order of first appearance.
std::vector<ImitationSummary> summarize(const std::vector<ImitationRow>& rows, bool by_target = false);

std::string rows_csv(const std::vector<ImitationRow>& rows);
// A Markdown table: policy, demonstrations (training / held-out experts), the target when the
// summaries are by target, n, median and mean |demo speed - imitation speed|, median achieved
// speed, fall rate.
std::string summary_table(const std::vector<ImitationSummary>& summaries);

// How we count modes (mode collapse, issue 5): a target speed counts as covered by a set of
// average speeds when at least `min_fraction` of them lie within `radius` m/s of it.
struct ModeCoverageOptions {
  double radius = 0.5, min_fraction = 0.05;
};

struct ModeCoverage {
  std::string source;  // "demonstrations" or a policy name
  std::vector<double> fractions;  // per target, the share of speeds within the radius
  int covered = 0;
};

ModeCoverage mode_coverage(const std::string& source, const std::vector<double>& speeds,
                           const std::vector<double>& targets, const ModeCoverageOptions& options = {});

// Coverage of the demonstrations' speeds and of each policy's achieved speeds on the training
// experts' demonstrations, over the distinct targets of those demonstrations.
std::vector<ModeCoverage> mode_coverages(const std::vector<ImitationRow>& rows,
                                         const ModeCoverageOptions& options = {});
// A Markdown table: source, the share near each target, modes covered.
std::string mode_table(const std::vector<ModeCoverage>& coverages, const std::vector<double>& targets);
// The distinct targets of the training experts' rows, ascending.
std::vector<double> distinct_targets(const std::vector<ImitationRow>& rows);

}  // namespace vaegail::eval
