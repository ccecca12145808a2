#include "eval/body_eval.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace vaegail::eval {

namespace {

int index_of(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

std::string short_number(double v) { return fmt::format("{:.4g}", v); }

}  // namespace

std::vector<std::string> shared_features(const Env& env, const DemoHeader& header) {
  std::vector<std::string> out;
  for (const auto& f : env.feature_names())
    if (std::find(header.feature_names.begin(), header.feature_names.end(), f) != header.feature_names.end())
      out.push_back(f);
  return out;
}

std::vector<double> feature_errors(const Episode& demo, const DemoHeader& header, const Episode& imitation,
                                   const Env& env, const std::vector<std::string>& features) {
  const int nd = static_cast<int>(header.feature_names.size()), ni = static_cast<int>(env.feature_names().size());
  const int steps = std::min(demo.length(), imitation.length());
  std::vector<double> errors;
  for (const auto& f : features) {
    const int d = index_of(header.feature_names, f), i = index_of(env.feature_names(), f);
    double sum = 0;
    // Step t's state is the one the t-th action reached; row 0 is the shared initial state.
    for (int t = 1; t <= steps; ++t)
      sum += std::abs(imitation.features[static_cast<size_t>(t) * ni + i] - demo.features[static_cast<size_t>(t) * nd + d]);
    errors.push_back(steps > 0 ? sum / steps : 0.0);
  }
  return errors;
}

BodyEval evaluate_body(const Env& prototype, const DemoSet& demos, const std::vector<int64_t>& episodes,
                       const torch::Tensor& z, const std::vector<NamedPolicy>& policies,
                       const vae::ImitationOptions& options, Progress* progress, const ImitationScorer& score) {
  BodyEval out;
  out.features = shared_features(prototype, demos.header);
  vae::ImitationOptions o = options;
  o.speed_feature.clear();  // a body's speed is one feature among the scored ones
  const auto starts = vae::rollout_starts(demos, episodes);
  for (const auto& p : policies) {
    const auto outcomes = vae::roll_out_latent_policy(prototype, starts, z, p.policy, o, progress);
    for (size_t k = 0; k < episodes.size(); ++k) {
      const Episode& demo = demos.episodes[episodes[k]];
      BodyRow row;
      row.policy = p.name;
      row.expert_id = demo.expert_id;
      row.episode = episodes[k];
      row.fell = outcomes[k].fell;
      row.fall_step = outcomes[k].fall_step;
      row.steps = outcomes[k].episode.length();
      row.demo_steps = demo.length();
      row.feature_errors = feature_errors(demo, demos.header, outcomes[k].episode, prototype, out.features);
      if (score) score(row, outcomes[k].episode);
      out.rows.push_back(std::move(row));
    }
  }
  return out;
}

std::string body_rows_csv(const BodyEval& eval) {
  std::string csv = "policy,episode,expert_id,fell,fall_step,steps,demo_steps";
  for (const auto& f : eval.features) csv += ",error_" + f;
  csv += "\n";
  for (const auto& r : eval.rows) {
    csv += r.policy + "," + std::to_string(r.episode) + "," + r.expert_id + "," + (r.fell ? "1" : "0") + "," +
           std::to_string(r.fall_step) + "," + std::to_string(r.steps) + "," + std::to_string(r.demo_steps);
    for (double e : r.feature_errors) csv += "," + short_number(e);
    csv += "\n";
  }
  return csv;
}

std::string body_summary_table(const BodyEval& eval) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const BodyRow*>> by_policy;
  for (const auto& r : eval.rows) {
    if (!by_policy.count(r.policy)) order.push_back(r.policy);
    by_policy[r.policy].push_back(&r);
  }
  std::string table = "| policy | imitations | fall rate | mean steps (demo) |";
  std::string rule = "|---|---|---|---|";
  for (const auto& f : eval.features) {
    table += " " + f + " error |";
    rule += "---|";
  }
  table += "\n" + rule + "\n";
  for (const auto& policy : order) {
    const auto& rows = by_policy[policy];
    double falls = 0, steps = 0, demo_steps = 0;
    std::vector<double> errors(eval.features.size(), 0.0);
    for (const BodyRow* r : rows) {
      falls += r->fell;
      steps += r->steps;
      demo_steps += r->demo_steps;
      for (size_t f = 0; f < errors.size(); ++f) errors[f] += r->feature_errors[f];
    }
    const double n = static_cast<double>(rows.size());
    table += "| " + policy + " | " + std::to_string(rows.size()) + " | " + short_number(falls / n) + " | " +
             short_number(steps / n) + " (" + short_number(demo_steps / n) + ") |";
    for (double e : errors) table += " " + short_number(e / n) + " |";
    table += "\n";
  }
  return table;
}

}  // namespace vaegail::eval
