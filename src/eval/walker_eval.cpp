#include "eval/walker_eval.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <map>

#include "util/progress.h"
#include "vae/demo_dataset.h"

namespace vaegail::eval {

std::vector<int64_t> episodes_per_expert(const DemoSet& demos, int per_expert) {
  std::map<std::string, int> taken;
  std::vector<int64_t> chosen;
  for (int64_t i = 0; i < static_cast<int64_t>(demos.episodes.size()); ++i)
    if (taken[demos.episodes[i].expert_id]++ < per_expert) chosen.push_back(i);
  return chosen;
}

std::vector<ImitationRow> imitate_with_policies(const Env& prototype, const DemoSet& demos,
                                                const std::vector<int64_t>& episodes, const torch::Tensor& z,
                                                const std::vector<NamedPolicy>& policies,
                                                const vae::ImitationOptions& options, Progress* progress) {
  if (z.size(0) != static_cast<int64_t>(episodes.size()))
    throw std::invalid_argument("imitate_with_policies: " + std::to_string(z.size(0)) + " embeddings for " +
                                std::to_string(episodes.size()) + " episodes");
  const auto starts = vae::rollout_starts(demos, episodes);
  std::vector<ImitationRow> rows;
  for (const auto& p : policies) {
    const auto outcomes = vae::roll_out_latent_policy(prototype, starts, z, p.policy, options, progress);
    for (size_t j = 0; j < episodes.size(); ++j) {
      const Episode& e = demos.episodes[episodes[j]];
      ImitationRow r;
      r.policy = p.name;
      r.expert_id = e.expert_id;
      r.episode = episodes[j];
      r.target = e.context.empty() ? std::nan("") : e.context[0];
      r.held_out = vae::is_held_out(e);
      r.demo_speed = vae::achieved_speed(demos, episodes[j]);
      r.achieved_speed = outcomes[j].achieved_speed;
      r.fell = outcomes[j].fell;
      rows.push_back(r);
    }
  }
  return rows;
}

std::vector<ImitationSummary> summarize(const std::vector<ImitationRow>& rows, bool by_target) {
  const auto same_group = [by_target](const ImitationSummary& s, const ImitationRow& r) {
    return s.policy == r.policy && s.held_out == r.held_out && (!by_target || s.target == r.target);
  };
  std::vector<ImitationSummary> out;
  for (const auto& r : rows) {
    if (std::any_of(out.begin(), out.end(), [&](const ImitationSummary& s) { return same_group(s, r); })) continue;
    ImitationSummary s;
    s.policy = r.policy;
    s.held_out = r.held_out;
    if (by_target) s.target = r.target;
    std::vector<double> demo, achieved;
    for (const auto& q : rows) {
      if (!same_group(s, q)) continue;
      demo.push_back(q.demo_speed);
      achieved.push_back(q.achieved_speed);
      s.mean_abs_difference += q.abs_difference();
      s.fall_rate += q.fell;
    }
    s.demonstrations = static_cast<int>(demo.size());
    s.mean_abs_difference /= s.demonstrations;
    s.fall_rate /= s.demonstrations;
    s.median_abs_difference = vae::median_abs_difference(demo, achieved);
    s.median_achieved_speed = vae::median(achieved);
    out.push_back(s);
  }
  return out;
}

std::string rows_csv(const std::vector<ImitationRow>& rows) {
  std::string csv = "policy,episode,expert_id,target,held_out,demo_speed,achieved_speed,abs_diff,fell\n";
  for (const auto& r : rows)
    fmt::format_to(std::back_inserter(csv), "{},{},{},{:.9g},{},{:.6f},{:.6f},{:.6f},{}\n", r.policy, r.episode,
                   r.expert_id, r.target, r.held_out ? 1 : 0, r.demo_speed, r.achieved_speed, r.abs_difference(),
                   r.fell ? 1 : 0);
  return csv;
}

std::string summary_table(const std::vector<ImitationSummary>& summaries) {
  const bool by_target = std::any_of(summaries.begin(), summaries.end(),
                                     [](const ImitationSummary& s) { return !std::isnan(s.target); });
  std::string table = std::string("| policy | demonstrations | ") + (by_target ? "target (m/s) | " : "") +
                      "n | median \\|Δspeed\\| (m/s) | mean \\|Δspeed\\| (m/s) | median speed (m/s) | falls |\n" +
                      "|---|---|" + (by_target ? "---:|" : "") + "---:|---:|---:|---:|---:|\n";
  for (const auto& s : summaries) {
    const std::string target = by_target ? fmt::format(" {:g} |", s.target) : "";
    table += fmt::format("| {} | {} |{} {} | {:.3f} | {:.3f} | {:.3f} | {:.1f}% |\n", s.policy,
                         s.held_out ? "held-out experts (one-shot)" : "training experts", target, s.demonstrations,
                         s.median_abs_difference, s.mean_abs_difference, s.median_achieved_speed, 100.0 * s.fall_rate);
  }
  return table;
}

ModeCoverage mode_coverage(const std::string& source, const std::vector<double>& speeds,
                           const std::vector<double>& targets, const ModeCoverageOptions& options) {
  ModeCoverage c{source, {}, 0};
  for (const double target : targets) {
    const auto near = std::count_if(speeds.begin(), speeds.end(),
                                    [&](double v) { return std::abs(v - target) <= options.radius; });
    const double fraction = speeds.empty() ? 0.0 : static_cast<double>(near) / speeds.size();
    c.fractions.push_back(fraction);
    c.covered += fraction >= options.min_fraction;
  }
  return c;
}

std::vector<double> distinct_targets(const std::vector<ImitationRow>& rows) {
  std::vector<double> targets;
  for (const auto& r : rows)
    if (!r.held_out && !std::isnan(r.target) && std::find(targets.begin(), targets.end(), r.target) == targets.end())
      targets.push_back(r.target);
  std::sort(targets.begin(), targets.end());
  return targets;
}

std::vector<ModeCoverage> mode_coverages(const std::vector<ImitationRow>& rows, const ModeCoverageOptions& options) {
  const auto targets = distinct_targets(rows);
  std::vector<std::string> policies;
  std::vector<double> demo;
  for (const auto& r : rows) {
    if (r.held_out) continue;
    if (std::find(policies.begin(), policies.end(), r.policy) == policies.end()) policies.push_back(r.policy);
    if (r.policy == policies.front()) demo.push_back(r.demo_speed);
  }
  std::vector<ModeCoverage> out{mode_coverage("demonstrations", demo, targets, options)};
  for (const auto& p : policies) {
    std::vector<double> achieved;
    for (const auto& r : rows)
      if (!r.held_out && r.policy == p) achieved.push_back(r.achieved_speed);
    out.push_back(mode_coverage(p, achieved, targets, options));
  }
  return out;
}

std::string mode_table(const std::vector<ModeCoverage>& coverages, const std::vector<double>& targets) {
  std::string table = "| speeds of |", rule = "|---|";
  for (const double t : targets) {
    table += fmt::format(" near {:g} m/s |", t);
    rule += "---:|";
  }
  table += " modes covered |\n" + rule + "---:|\n";
  for (const auto& c : coverages) {
    table += "| " + c.source + " |";
    for (const double f : c.fractions) table += fmt::format(" {:.0f}% |", 100.0 * f);
    table += fmt::format(" {} of {} |\n", c.covered, targets.size());
  }
  return table;
}

}  // namespace vaegail::eval
