#include "data/demo_stats.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <limits>

namespace vaegail {

Moments moments(const std::vector<double>& values) {
  Moments m;
  m.count = static_cast<long>(values.size());
  if (values.empty()) return m;
  double sum = 0, sq = 0;
  m.min = std::numeric_limits<double>::infinity();
  m.max = -m.min;
  for (double v : values) {
    sum += v;
    m.min = std::min(m.min, v);
    m.max = std::max(m.max, v);
  }
  m.mean = sum / values.size();
  for (double v : values) sq += (v - m.mean) * (v - m.mean);
  m.std = std::sqrt(sq / values.size());
  return m;
}

DemoSummary summarize(const DemoSet& set) {
  DemoSummary s;
  const auto& names = set.header.feature_names;
  const int nf = static_cast<int>(names.size());
  s.feature_names = names;
  std::vector<double> lengths;
  std::vector<std::vector<double>> steps(nf), means(nf);
  for (const Episode& e : set.episodes) {
    ++s.episodes;
    s.steps += e.length();
    lengths.push_back(e.length());
    if (e.length() > 0 && e.terminations.back()) ++s.terminated_episodes;
    ++s.episodes_per_context[e.context];
    ++s.episodes_per_expert[e.expert_id];
    for (int f = 0; f < nf; ++f) {
      for (int t = 1; t <= e.length(); ++t) steps[f].push_back(e.features[static_cast<size_t>(t) * nf + f]);
      means[f].push_back(e.mean_feature(f, nf));
    }
  }
  s.lengths = moments(lengths);
  for (int f = 0; f < nf; ++f) {
    s.per_step.push_back(moments(steps[f]));
    s.episode_mean.push_back(moments(means[f]));
  }
  return s;
}

namespace {
std::string context_text(const std::vector<double>& c) {
  std::string s;
  for (size_t i = 0; i < c.size(); ++i) s += fmt::format("{}{:g}", i ? ", " : "", c[i]);
  return s.empty() ? "(none)" : s;
}
}  // namespace

std::string format_summary(const DemoSet& set, const DemoSummary& s) {
  std::string out;
  const auto add = std::back_inserter(out);
  const auto& h = set.header;
  fmt::format_to(add, "file          {}\n", set.path);
  fmt::format_to(add, "env           {} (obs {}, act {}, control step {:g} s)\n", h.env_id, h.obs_dim(), h.act_dim(),
                 h.control_timestep);
  fmt::format_to(add, "episodes      {} ({} steps; length mean {:.1f}, min {:g}, max {:g})\n", s.episodes, s.steps,
                 s.lengths.mean, s.lengths.min, s.lengths.max);
  fmt::format_to(add, "terminated    {} episodes ended before the time limit\n", s.terminated_episodes);
  fmt::format_to(add, "experts       {}\n", s.episodes_per_expert.size());
  std::string ctx_names;
  for (const auto& n : h.context_names) ctx_names += (ctx_names.empty() ? "" : ", ") + n;
  fmt::format_to(add, "\nepisodes per context ({})\n", ctx_names.empty() ? "none" : ctx_names);
  for (const auto& [context, count] : s.episodes_per_context)
    fmt::format_to(add, "  {:<20} {}\n", context_text(context), count);
  fmt::format_to(add, "\n{:<16} {:>10} {:>10} {:>10} {:>10}   {}\n", "feature", "mean", "std", "min", "max",
                 "episode means: mean, std, min, max");
  for (size_t f = 0; f < s.feature_names.size(); ++f) {
    const Moments& a = s.per_step[f];
    const Moments& b = s.episode_mean[f];
    fmt::format_to(add, "{:<16} {:10.4g} {:10.4g} {:10.4g} {:10.4g}   {:.4g}, {:.4g}, {:.4g}, {:.4g}\n",
                   s.feature_names[f], a.mean, a.std, a.min, a.max, b.mean, b.std, b.min, b.max);
  }
  return out;
}

}  // namespace vaegail
