#include "data/demo_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
  char buf[32];
  for (size_t i = 0; i < c.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%g", i ? ", " : "", c[i]);
    s += buf;
  }
  return s.empty() ? "(none)" : s;
}
}  // namespace

std::string format_summary(const DemoSet& set, const DemoSummary& s) {
  std::string out;
  char line[256];
  auto add = [&](const char* fmt, auto... args) {
    std::snprintf(line, sizeof line, fmt, args...);
    out += line;
  };
  const auto& h = set.header;
  add("file          %s\n", set.path.c_str());
  add("env           %s (obs %d, act %d, control step %g s)\n", h.env_id.c_str(), h.obs_dim(),
      h.act_dim(), h.control_timestep);
  add("episodes      %d (%ld steps; length mean %.1f, min %g, max %g)\n", s.episodes, s.steps,
      s.lengths.mean, s.lengths.min, s.lengths.max);
  add("terminated    %d episodes ended before the time limit\n", s.terminated_episodes);
  add("experts       %zu\n", s.episodes_per_expert.size());
  std::string ctx_names;
  for (const auto& n : h.context_names) ctx_names += (ctx_names.empty() ? "" : ", ") + n;
  add("\nepisodes per context (%s)\n", ctx_names.empty() ? "none" : ctx_names.c_str());
  for (const auto& [context, count] : s.episodes_per_context)
    add("  %-20s %d\n", context_text(context).c_str(), count);
  add("\n%-16s %10s %10s %10s %10s   %s\n", "feature", "mean", "std", "min", "max", "episode means: mean, std, min, max");
  for (size_t f = 0; f < s.feature_names.size(); ++f) {
    const Moments& a = s.per_step[f];
    const Moments& b = s.episode_mean[f];
    add("%-16s %10.4g %10.4g %10.4g %10.4g   %.4g, %.4g, %.4g, %.4g\n", s.feature_names[f].c_str(), a.mean,
        a.std, a.min, a.max, b.mean, b.std, b.min, b.max);
  }
  return out;
}

}  // namespace vaegail
