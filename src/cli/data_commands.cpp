#include <cstdio>
#include <map>
#include <memory>

#include "cli/commands.h"
#include "data/demo_stats.h"
#include "plot/charts.h"

namespace vaegail::cli {
namespace {

struct InfoOptions {
  std::string path, histogram, feature = "com_speed";
  int bins = 30;
};

// "target_speed 1.5" for a one-value context, "a=1, b=2" for several.
std::string context_label(const std::vector<double>& context, const std::vector<std::string>& names) {
  if (context.empty()) return "all episodes";
  std::string label;
  char value[32];
  for (size_t i = 0; i < context.size(); ++i) {
    std::snprintf(value, sizeof value, "%g", context[i]);
    const std::string name = i < names.size() ? names[i] : "context_" + std::to_string(i);
    label += (i ? ", " : "") + (context.size() == 1 ? name + " " : name + "=") + value;
  }
  return label;
}

// Each episode's mean of `feature`: the recorded attribute mean_<feature> when there is one
// (the recorder stores it), else computed from the per-step features. One series per context.
std::vector<plot::HistogramSeries> episode_means_by_context(const DemoSet& set, const std::string& feature) {
  const auto& names = set.header.feature_names;
  const int nf = static_cast<int>(names.size());
  int f = -1;
  for (int i = 0; i < nf; ++i)
    if (names[i] == feature) f = i;
  std::map<std::vector<double>, std::vector<double>> by_context;
  for (size_t e = 0; e < set.episodes.size(); ++e) {
    const Episode& episode = set.episodes[e];
    const auto attribute = episode.attributes.find("mean_" + feature);
    if (attribute == episode.attributes.end() && f < 0) {
      std::string have;
      for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
      throw std::invalid_argument(set.path + ": episode " + std::to_string(e) + " has no feature '" +
                                  feature + "' nor attribute 'mean_" + feature + "' (features: " + have + ")");
    }
    by_context[episode.context].push_back(attribute != episode.attributes.end()
                                              ? attribute->second
                                              : episode.mean_feature(f, nf));
  }
  std::vector<plot::HistogramSeries> series;
  for (auto& [context, means] : by_context)
    series.push_back({context_label(context, set.header.context_names), std::move(means)});
  return series;
}

void run_info(const InfoOptions& o) {
  const DemoSet set = read_demos(o.path);
  // Checked before anything is printed, so a bad --feature gives only the error.
  const auto series = o.histogram.empty() ? std::vector<plot::HistogramSeries>{}
                                          : episode_means_by_context(set, o.feature);
  std::fputs(format_summary(set, summarize(set)).c_str(), stdout);
  if (o.histogram.empty()) return;
  const auto edges = plot::even_bin_edges(series, o.bins);
  const std::string what = "episode mean " + o.feature;
  std::printf("\ndistribution of %s (episodes per bin)\n", what.c_str());
  std::fputs(plot::histogram_table(edges, series).c_str(), stdout);
  plot::histogram_chart({"distribution of " + what, what, "episodes"}, edges, series).save_png(o.histogram);
  std::printf("wrote %s\n", o.histogram.c_str());
}

}  // namespace

void add_data_commands(CLI::App& app) {
  CLI::App* data = app.add_subcommand("data", "inspect demonstration files");
  data->require_subcommand(1);
  auto options = std::make_shared<InfoOptions>();
  CLI::App* info = data->add_subcommand("info", "episodes, lengths, counts per context and feature statistics");
  info->add_option("file", options->path, "demonstration file (.h5)")->required();
  info->add_option("--histogram", options->histogram,
                   "also draw the distribution of episodes' mean --feature, one series per context, "
                   "to this PNG (the paper's Fig. 4 top right) and print it as a table");
  info->add_option("--feature", options->feature, "feature whose per-episode mean is counted")->capture_default_str();
  info->add_option("--bins", options->bins, "equal-width bins")->check(CLI::Range(1, 10000))->capture_default_str();
  info->callback([options] { run_info(*options); });
}

}  // namespace vaegail::cli
