// What `vaegail data info` prints: episode counts and lengths, episodes per context, and
// statistics of every feature, per step and per episode mean.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "data/demos.h"

namespace vaegail {

struct Moments {
  long count = 0;
  double mean = 0, std = 0, min = 0, max = 0;
};
Moments moments(const std::vector<double>& values);

struct DemoSummary {
  int episodes = 0;
  long steps = 0;
  Moments lengths;
  int terminated_episodes = 0;       // ended by termination (fell) rather than the time limit
  std::map<std::vector<double>, int> episodes_per_context;
  std::map<std::string, int> episodes_per_expert;
  std::vector<std::string> feature_names;
  std::vector<Moments> per_step;     // one per feature, over all steps
  std::vector<Moments> episode_mean; // one per feature, over episodes' means
};

DemoSummary summarize(const DemoSet& set);
std::string format_summary(const DemoSet& set, const DemoSummary& summary);

}  // namespace vaegail
