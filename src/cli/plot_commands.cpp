// `vaegail plot ...`: figures from the CSV files the other stages write (metrics logs, VAE
// embeddings), drawn by scripts/plot/ (cli/figures.h).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/figures.h"
#include "eval/tsne.h"
#include "util/atomic_file.h"
#include "util/csv_table.h"
#include "util/histogram.h"

namespace vaegail::cli {
namespace {

std::vector<std::string> split_names(const std::string& list) {
  std::vector<std::string> names;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');)
    if (!name.empty()) names.push_back(name);
  return names;
}

// What every figure command has: where it goes, its title and size.
struct FigureOptions {
  std::string out, title;
  int width = 960, height = 640;
  std::vector<std::string> args() const {
    std::vector<std::string> a{"--out", out, "--width", std::to_string(width), "--height", std::to_string(height)};
    if (!title.empty()) a.insert(a.end(), {"--title", title});
    return a;
  }
};

void add_figure_options(CLI::App& command, FigureOptions& o, const std::string& default_title) {
  command.add_option("--out", o.out, "figure to write; .png, .svg or .pdf")->required();
  command.add_option("--title", o.title, "figure title (default: " + default_title + ")");
  command.add_option("--width", o.width, "width in pixels")->check(CLI::Range(64, 20000))->capture_default_str();
  command.add_option("--height", o.height, "height in pixels")->check(CLI::Range(64, 20000))->capture_default_str();
}

struct CurvesOptions {
  std::string csv, x = "epoch", y;
  bool log_y = false;
  FigureOptions figure;
};

void run_curves(const CurvesOptions& o) {
  require_plotting("plot curves");
  if (split_names(o.y).empty()) throw std::invalid_argument("--y: name at least one column");
  std::vector<std::string> args{"--csv", o.csv, "--x", o.x, "--y", o.y};
  if (o.log_y) args.push_back("--log-y");
  for (const auto& a : o.figure.args()) args.push_back(a);
  draw_figure("curves.py", args);
  std::printf("wrote %s\n", o.figure.out.c_str());
}

struct TsneCommandOptions {
  std::string embeddings, color = "achieved_speed", coords_out;
  bool training_only = false;
  eval::TsneOptions tsne;
  FigureOptions figure;
};

// The rows of the embedding table to map: all, or those with held_out = 0.
std::vector<int> selected_rows(const CsvTable& table, bool training_only) {
  std::vector<int> rows;
  const auto held_out = training_only ? table.numbers("held_out") : std::vector<double>(table.rows(), 0);
  for (int r = 0; r < table.rows(); ++r)
    if (held_out[r] == 0) rows.push_back(r);
  return rows;
}

std::vector<std::string> latent_columns(const CsvTable& table, const std::string& where) {
  std::vector<std::string> names;
  while (table.has_column("mu_" + std::to_string(names.size())))
    names.push_back("mu_" + std::to_string(names.size()));
  if (names.empty()) throw std::invalid_argument(where + ": no latent columns mu_0, mu_1, ...");
  return names;
}

// The input's descriptive columns (not mu_*/sigma_*) of the mapped rows, then tsne_x, tsne_y.
std::string coordinates_csv(const CsvTable& table, const std::vector<int>& rows,
                            const std::vector<double>& embedding) {
  std::vector<std::string> kept;
  for (const auto& c : table.columns())
    if (c.rfind("mu_", 0) != 0 && c.rfind("sigma_", 0) != 0) kept.push_back(c);
  std::vector<std::vector<std::string>> cells;
  for (const auto& c : kept) cells.push_back(table.strings(c));
  std::string out;
  for (const auto& c : kept) out += c + ",";
  out += "tsne_x,tsne_y\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    for (const auto& column : cells) out += column[rows[i]] + ",";
    out += fmt::format("{:.9g},{:.9g}\n", embedding[2 * i], embedding[2 * i + 1]);
  }
  return out;
}

// Where the coordinates go for the script: --coords-out, or a temporary file removed afterwards.
class CoordinatesFile {
 public:
  explicit CoordinatesFile(const std::string& kept)
      : path_(kept.empty() ? (std::filesystem::temp_directory_path() /
                              ("vaegail-tsne-" + std::to_string(getpid()) + ".csv")).string()
                           : kept),
        temporary_(kept.empty()) {}
  ~CoordinatesFile() {
    if (temporary_) std::remove(path_.c_str());
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  bool temporary_;
};

void run_tsne(const TsneCommandOptions& o) {
  require_plotting("plot tsne");  // before the minutes of t-SNE
  const auto table = CsvTable::read(o.embeddings);
  const auto rows = selected_rows(table, o.training_only);
  const auto latents = latent_columns(table, o.embeddings);
  table.numbers(o.color);  // the colour column is there and numeric
  const int n = static_cast<int>(rows.size()), d = static_cast<int>(latents.size());
  std::vector<double> data(static_cast<size_t>(n) * d);
  for (int k = 0; k < d; ++k) {
    const auto column = table.numbers(latents[k]);
    for (int i = 0; i < n; ++i) data[static_cast<size_t>(i) * d + k] = column[rows[i]];
  }
  const auto result = eval::tsne(data, n, d, o.tsne);
  const CoordinatesFile coordinates(o.coords_out);
  write_file_atomically(coordinates.path(), coordinates_csv(table, rows, result.embedding));
  FigureOptions figure = o.figure;
  if (figure.title.empty()) figure.title = fmt::format("t-SNE of {} embeddings (perplexity {:g})", n, o.tsne.perplexity);
  std::vector<std::string> args{"--csv", coordinates.path(), "--x", "tsne_x", "--y", "tsne_y", "--color", o.color,
                                "--xlabel", "t-SNE 1", "--ylabel", "t-SNE 2"};
  for (const auto& a : figure.args()) args.push_back(a);
  draw_figure("scatter.py", args);
  std::printf("wrote %s: %d points of %d dimensions, KL(P||Q) %.4f\n", figure.out.c_str(), n, d,
              result.kl_divergence);
  if (!o.coords_out.empty()) std::printf("wrote %s\n", o.coords_out.c_str());
}

struct HistogramOptions {
  std::string csv, column, group_by;
  int bins = 40;
  FigureOptions figure;
};

// Groups in numeric order when every group name is a number (target speeds), else in order of
// first appearance, as histogram.py orders them.
std::vector<HistogramSeries> grouped(const std::vector<double>& values, const std::vector<std::string>& groups,
                                     const std::string& group_column) {
  std::vector<std::pair<std::string, std::vector<double>>> ordered;
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < values.size(); ++i) {
    const auto [it, added] = index.emplace(groups[i], ordered.size());
    if (added) ordered.push_back({groups[i], {}});
    ordered[it->second].second.push_back(values[i]);
  }
  auto number = [](const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    return (!s.empty() && *end == '\0') ? v : NAN;
  };
  const bool numeric = std::all_of(ordered.begin(), ordered.end(),
                                   [&](const auto& g) { return !std::isnan(number(g.first)); });
  if (numeric)
    std::stable_sort(ordered.begin(), ordered.end(),
              [&](const auto& a, const auto& b) { return number(a.first) < number(b.first); });
  std::vector<HistogramSeries> series;
  for (auto& [name, group_values] : ordered)
    series.push_back({group_column + " " + name, std::move(group_values)});
  return series;
}

void run_histogram(const HistogramOptions& o) {
  require_plotting("plot histogram");
  const auto table = CsvTable::read(o.csv);
  const auto values = table.numbers(o.column);
  if (values.empty()) throw std::invalid_argument(o.csv + ": no rows to plot");
  const auto series = o.group_by.empty() ? std::vector<HistogramSeries>{{"", values}}
                                         : grouped(values, table.strings(o.group_by), o.group_by);
  const auto edges = even_bin_edges(series, o.bins);
  FigureOptions figure = o.figure;
  if (figure.title.empty()) figure.title = "distribution of " + o.column;
  std::vector<std::string> args{"--csv", o.csv, "--column", o.column, "--bins", std::to_string(o.bins)};
  if (!o.group_by.empty()) args.insert(args.end(), {"--group-by", o.group_by, "--group-prefix", o.group_by + " "});
  for (const auto& a : figure.args()) args.push_back(a);
  draw_figure("histogram.py", args);
  std::fputs(histogram_table(edges, series).c_str(), stdout);
  std::printf("wrote %s: %d values in %zu series\n", figure.out.c_str(), table.rows(), series.size());
}

}  // namespace

void add_plot_commands(CLI::App& app) {
  CLI::App* plot = app.add_subcommand("plot", "draw figures from metrics and embedding CSV files (python3-matplotlib, scripts/plot/)");
  plot->require_subcommand(1);

  auto curves = std::make_shared<CurvesOptions>();
  CLI::App* curves_cmd = plot->add_subcommand("curves", "line chart of CSV columns, e.g. training curves");
  curves_cmd->add_option("--csv", curves->csv, "CSV with a header row (e.g. run/metrics.csv)")->required();
  curves_cmd->add_option("--x", curves->x, "column on the x axis")->capture_default_str();
  curves_cmd->add_option("--y", curves->y, "comma-separated columns to draw")->required();
  curves_cmd->add_flag("--log-y", curves->log_y, "logarithmic y axis (values must be positive)");
  add_figure_options(*curves_cmd, curves->figure, "the CSV path");
  curves_cmd->callback([curves] { run_curves(*curves); });

  auto tsne = std::make_shared<TsneCommandOptions>();
  CLI::App* tsne_cmd = plot->add_subcommand(
      "tsne", "t-SNE of VAE embeddings (vaegail vae embed), coloured by a column (paper Fig. 4 left)");
  tsne_cmd->add_option("--embeddings", tsne->embeddings, "embedding CSV (episode,...,mu_*,sigma_*)")->required();
  add_figure_options(*tsne_cmd, tsne->figure, "t-SNE of N embeddings (perplexity P)");
  tsne_cmd->add_option("--color", tsne->color, "numeric column that colours the points")->capture_default_str();
  tsne_cmd->add_option("--perplexity", tsne->tsne.perplexity, "effective number of neighbours")
      ->check(CLI::Range(1.0, 1e6))->capture_default_str();
  tsne_cmd->add_option("--iterations", tsne->tsne.iterations, "gradient steps")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  tsne_cmd->add_option("--seed", tsne->tsne.seed, "seed of the initial layout")->capture_default_str();
  tsne_cmd->add_flag("--training-only", tsne->training_only, "leave out rows with held_out = 1");
  tsne_cmd->add_option("--coords-out", tsne->coords_out, "also write the 2-D coordinates as CSV");
  tsne_cmd->callback([tsne] { run_tsne(*tsne); });

  auto histogram = std::make_shared<HistogramOptions>();
  CLI::App* histogram_cmd = plot->add_subcommand("histogram", "overlaid histograms of a CSV column, one per group");
  histogram_cmd->add_option("--csv", histogram->csv, "CSV with a header row")->required();
  histogram_cmd->add_option("--column", histogram->column, "numeric column to count")->required();
  histogram_cmd->add_option("--group-by", histogram->group_by, "column whose values split the rows into series");
  histogram_cmd->add_option("--bins", histogram->bins, "equal-width bins over the column's range")
      ->check(CLI::Range(1, 10000))->capture_default_str();
  add_figure_options(*histogram_cmd, histogram->figure, "distribution of COLUMN");
  histogram_cmd->callback([histogram] { run_histogram(*histogram); });
}

}  // namespace vaegail::cli
