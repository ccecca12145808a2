#include "eval/humanoid_eval.h"

#include <algorithm>
#include <fmt/format.h>
#include <iterator>

#include "eval/body_eval.h"
#include "experts/humanoid_gait.h"

namespace vaegail::eval {

std::vector<HumanoidRow> evaluate_humanoid(const Env& prototype, const DemoSet& demos, const std::string& set,
                                           const std::vector<int64_t>& episodes, const torch::Tensor& z,
                                           const std::vector<NamedPolicy>& policies,
                                           const vae::ImitationOptions& options, Progress* progress) {
  const double dt = prototype.control_timestep();
  const StyleClassifier classifier(demos, dt);
  std::vector<HumanoidRow> rows;
  const auto score = [&](const BodyRow& body, const Episode& imitation) {
    HumanoidRow r;
    r.set = set;
    r.policy = body.policy;
    r.style = body.expert_id;
    r.episode = body.episode;
    r.fell = body.fell;
    r.fall_step = body.fall_step;
    if (r.fell) r.fall_seconds = r.fall_step * dt;
    r.steps = body.steps;
    r.demo_steps = body.demo_steps;
    if (!r.fell) r.named_style = classifier.name(gait_signature(imitation, prototype.feature_names(), dt));
    rows.push_back(std::move(r));
  };
  evaluate_body(prototype, demos, episodes, z, policies, options, progress, score);
  return rows;
}

std::vector<HumanoidSummary> summarize_humanoid(const std::vector<HumanoidRow>& rows) {
  const auto in_order = [&rows](auto field) {
    std::vector<std::string> out;
    for (const auto& r : rows)
      if (std::find(out.begin(), out.end(), r.*field) == out.end()) out.push_back(r.*field);
    return out;
  };
  std::vector<HumanoidSummary> out;
  const auto summary = [&](const std::string& set, const std::string& style, const std::string& policy) {
    HumanoidSummary s{set, policy, style};
    double fall_seconds = 0;
    for (const auto& r : rows) {
      if (r.set != set || r.policy != policy || (style != "all" && r.style != style)) continue;
      ++s.imitations;
      s.falls += r.fell;
      s.kept_style += r.kept_style();
      if (r.fell) fall_seconds += r.fall_seconds;
    }
    if (s.falls) s.mean_fall_seconds = fall_seconds / s.falls;
    if (s.imitations) out.push_back(s);
  };
  const auto policies = in_order(&HumanoidRow::policy);
  for (const auto& set : in_order(&HumanoidRow::set)) {
    for (const auto& style : in_order(&HumanoidRow::style))
      for (const auto& policy : policies) summary(set, style, policy);
    for (const auto& policy : policies) summary(set, "all", policy);
  }
  return out;
}

std::string humanoid_rows_csv(const std::vector<HumanoidRow>& rows) {
  std::string csv = "set,policy,episode,style,fell,fall_step,fall_seconds,steps,demo_steps,named_style,kept_style\n";
  for (const auto& r : rows)
    fmt::format_to(std::back_inserter(csv), "{},{},{},{},{},{},{},{},{},{},{}\n", r.set, r.policy, r.episode, r.style,
                   r.fell ? 1 : 0, r.fall_step, r.fell ? fmt::format("{:.2f}", r.fall_seconds) : "", r.steps,
                   r.demo_steps, r.named_style, r.kept_style() ? 1 : 0);
  return csv;
}

namespace {
std::string percent(double fraction) { return std::isnan(fraction) ? "-" : fmt::format("{:.1f}%", 100 * fraction); }
}  // namespace

std::string humanoid_table(const std::vector<HumanoidSummary>& summaries) {
  std::string table =
      "| set | controller | policy | imitations | fell before the end | mean time of a fall | stayed up | "
      "kept the style (of those up) |\n|---|---|---|---:|---:|---:|---:|---:|\n";
  for (const auto& s : summaries)
    fmt::format_to(std::back_inserter(table), "| {} | {} | {} | {} | {} ({}) | {} | {} | {} ({} of {}) |\n", s.set,
                   s.style, s.policy, s.imitations, percent(s.fall_rate()), s.falls,
                   std::isnan(s.mean_fall_seconds) ? "-" : fmt::format("{:.2f} s", s.mean_fall_seconds), s.stayed_up(),
                   percent(s.kept_style_rate()), s.kept_style, s.stayed_up());
  return table;
}

nlohmann::json humanoid_json(const std::vector<HumanoidSummary>& summaries) {
  nlohmann::json list = nlohmann::json::array();
  const auto number = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  for (const auto& s : summaries)
    list.push_back({{"set", s.set},
                    {"style", s.style},
                    {"policy", s.policy},
                    {"imitations", s.imitations},
                    {"falls", s.falls},
                    {"fall_rate", number(s.fall_rate())},
                    {"mean_fall_seconds", number(s.mean_fall_seconds)},
                    {"stayed_up", s.stayed_up()},
                    {"kept_style", s.kept_style},
                    {"kept_style_rate", number(s.kept_style_rate())}});
  return {{"summaries", list}};
}

std::string humanoid_falls_csv(const std::vector<HumanoidSummary>& summaries) {
  std::string csv = "group,series,value\n";
  for (const auto& s : summaries) {
    if (s.style == "all") continue;
    // A controller's expert id names its set ("eval/drunk"); one that does not is named with it.
    const std::string group = s.style.rfind(s.set + "/", 0) == 0 ? s.style : s.set + ": " + s.style;
    fmt::format_to(std::back_inserter(csv), "{},{},{:.2f}\n", group, s.policy, 100 * s.fall_rate());
  }
  return csv;
}

}  // namespace vaegail::eval
