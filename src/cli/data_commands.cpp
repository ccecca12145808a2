#include <cstdio>
#include <iterator>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <memory>

#include "cli/commands.h"
#include "cli/figures.h"
#include "cli/task_options.h"
#include "data/demo_stats.h"
#include "data/foreign_demos.h"
#include "util/histogram.h"
#include "util/run_lock.h"

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
  for (size_t i = 0; i < context.size(); ++i) {
    const std::string value = fmt::format("{:g}", context[i]);
    const std::string name = i < names.size() ? names[i] : "context_" + std::to_string(i);
    label += (i ? ", " : "") + (context.size() == 1 ? name + " " : name + "=") + value;
  }
  return label;
}

// Each episode's mean of `feature`: the recorded attribute mean_<feature> when there is one
// (the recorder stores it), else computed from the per-step features. One series per context.
std::vector<HistogramSeries> episode_means_by_context(const DemoSet& set, const std::string& feature) {
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
  std::vector<HistogramSeries> series;
  for (auto& [context, means] : by_context)
    series.push_back({context_label(context, set.header.context_names), std::move(means)});
  return series;
}

void run_info(const InfoOptions& o) {
  const DemoSet set = read_demos(o.path);
  // Checked before anything is printed, so a bad --feature gives only the error.
  const auto series = o.histogram.empty() ? std::vector<HistogramSeries>{}
                                          : episode_means_by_context(set, o.feature);
  std::fputs(format_summary(set, summarize(set)).c_str(), stdout);
  if (o.histogram.empty()) return;
  const auto edges = even_bin_edges(series, o.bins);
  const std::string what = "episode mean " + o.feature;
  std::printf("\ndistribution of %s (episodes per bin)\n", what.c_str());
  std::fputs(histogram_table(edges, series).c_str(), stdout);
  const bool drawn = save_histogram_figure(o.histogram, series, o.bins, {"distribution of " + what, what, "episodes"});
  std::printf("wrote %s%s\n", drawn ? (o.histogram + " and ").c_str() : "", figure_data_path(o.histogram).c_str());
}

struct ImportOptions {
  std::string source, out, task;
  bool force = false;
};

void write_demo_set(const DemoSet& set, const std::string& path) {
  DemoWriter writer(path, set.header);
  for (const auto& e : set.episodes) writer.append(e);
  writer.commit();
}

std::int64_t total_steps(const DemoSet& set) {
  std::int64_t steps = 0;
  for (const auto& e : set.episodes) steps += e.length();
  return steps;
}

void run_import(const ImportOptions& o) {
  if (std::filesystem::exists(o.out) && !o.force) throw std::runtime_error(o.out + ": exists (pass --force to replace it)");
  const bool npz = o.source.size() > 4 && o.source.compare(o.source.size() - 4, 4, ".npz") == 0;
  DemoSet set = npz ? import_imitation_npz(o.source) : import_minari(o.source);
  if (!o.task.empty()) {
    TaskOptions task;
    task.task = o.task;
    adopt_env(set, *task.make());
  }
  write_demo_set(set, o.out);
  std::printf("wrote %s: %zu episodes, %lld steps, observation %d, action %d, task '%s'%s\n", o.out.c_str(),
              set.episodes.size(), static_cast<long long>(total_steps(set)), set.header.obs_dim(),
              set.header.act_dim(), set.header.env_id.c_str(),
              set.header.body_mjcf.empty() ? "" : " (body stored in the file)");
}

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool force = false;
};

// The first header component in which `b` differs from `a`, or empty: files merge only when
// recorded on one task with the same components.
std::string header_difference(const DemoHeader& a, const DemoHeader& b) {
  if (a.env_id != b.env_id) return "task '" + b.env_id + "', not '" + a.env_id + "'";
  if (a.control_timestep != b.control_timestep) return "another control timestep";
  if (a.observation_names != b.observation_names) return "other observation components";
  if (a.action_names != b.action_names) return "other action components";
  if (a.feature_names != b.feature_names) return "other features";
  if (a.context_names != b.context_names) return "other context components";
  if (a.body_mjcf != b.body_mjcf) return "another body";
  return "";
}

// DAgger's aggregate, or any union of demonstration sets of one task: the episodes of each file in
// the order given, headers checked to agree.
void run_merge(const MergeOptions& o) {
  const RunLock lock = lock_output_file(o.out);
  if (std::filesystem::exists(o.out) && !o.force) throw std::runtime_error(o.out + ": exists (pass --force to replace it)");
  DemoSet merged = read_demos(o.inputs.front());
  for (size_t k = 1; k < o.inputs.size(); ++k) {
    DemoSet more = read_demos(o.inputs[k]);
    const std::string difference = header_difference(merged.header, more.header);
    if (!difference.empty())
      throw std::invalid_argument(o.inputs[k] + ": cannot merge with " + o.inputs.front() + ": " + difference);
    std::move(more.episodes.begin(), more.episodes.end(), std::back_inserter(merged.episodes));
  }
  write_demo_set(merged, o.out);
  std::printf("wrote %s: %zu episodes, %lld steps, from %zu files\n", o.out.c_str(), merged.episodes.size(),
              static_cast<long long>(total_steps(merged)), o.inputs.size());
}

struct ExportOptions {
  std::string file, minari_dir, dataset_id;
  bool force = false;
};

void run_export(const ExportOptions& o) {
  const DemoSet set = read_demos(o.file);
  const std::string id = o.dataset_id.empty() ? "vaegail/" + std::filesystem::path(o.file).stem().string() + "-v0"
                                              : o.dataset_id;
  export_minari(set, o.minari_dir, id, o.force);
  std::printf("wrote %s/data/{main_data.hdf5, metadata.json}: dataset_id %s, %zu episodes, %lld steps\n",
              o.minari_dir.c_str(), id.c_str(), set.episodes.size(), static_cast<long long>(total_steps(set)));
}

void add_import_export(CLI::App& data) {
  auto in = std::make_shared<ImportOptions>();
  CLI::App* import = data.add_subcommand(
      "import", "demonstrations from a Minari dataset (DATASET/data/{metadata.json, main_data.hdf5}) or an "
                "imitation library .npz into a demonstration file");
  import->add_option("source", in->source,
                     "a Minari dataset: its directory, its data/ folder or its ID (e.g. D4RL/door/human-v2, looked up "
                     "under $MINARI_DATASETS_PATH, else ~/.minari/datasets); or imitation trajectories (.npz)")
      ->required();
  import->add_option("--out", in->out, "demonstration file to write (.h5)")->required();
  import->add_option("--task", in->task,
                     "the task or MJCF body the demonstrations were recorded on: names their components and stores "
                     "the body in the file, so later stages rebuild its environment (dimensions are checked)");
  import->add_flag("--force", in->force, "replace an existing output file");
  import->callback([in] { run_import(*in); });

  auto out = std::make_shared<ExportOptions>();
  CLI::App* exp = data.add_subcommand(
      "export", "write a demonstration file as a Minari dataset directory (DIR/data/{main_data.hdf5, metadata.json}; "
                "DIR = ~/.minari/datasets/ID makes it minari.load_dataset(ID)'s)");
  exp->add_option("file", out->file, "demonstration file (.h5)")->required();
  exp->add_option("--minari", out->minari_dir, "dataset directory to write (appears whole or not at all)")->required();
  exp->add_option("--dataset-id", out->dataset_id, "Minari's dataset_id (default: vaegail/FILE_STEM-v0)");
  exp->add_flag("--force", out->force, "replace an existing directory");
  exp->callback([out] { run_export(*out); });

  auto merge = std::make_shared<MergeOptions>();
  CLI::App* m = data.add_subcommand(
      "merge", "concatenate demonstration files of one task into one (DAgger's aggregate), episodes in the order given");
  m->add_option("inputs", merge->inputs, "demonstration files (.h5), their headers alike")->required()->check(CLI::ExistingFile);
  m->add_option("--out", merge->out, "demonstration file to write (.h5)")->required();
  m->add_flag("--force", merge->force, "replace an existing output file");
  m->callback([merge] { run_merge(*merge); });
}

}  // namespace

void add_data_commands(CLI::App& app) {
  CLI::App* data = app.add_subcommand("data", "inspect, import, export and merge demonstration files");
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
  add_import_export(*data);
}

}  // namespace vaegail::cli
