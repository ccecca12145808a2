// `vaegail plot ...`: figures from the CSV files the other stages write (metrics logs, VAE
// embeddings), so a run can be looked at without Python.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "eval/tsne.h"
#include "plot/charts.h"
#include "plot/csv_table.h"
#include "util/atomic_file.h"

namespace vaegail::cli {
namespace {

std::vector<std::string> split_names(const std::string& list) {
  std::vector<std::string> names;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');)
    if (!name.empty()) names.push_back(name);
  return names;
}

struct CurvesOptions {
  std::string csv, x = "epoch", y, out, title;
  bool log_y = false;
};

void run_curves(const CurvesOptions& o) {
  const auto table = plot::CsvTable::read(o.csv);
  const auto columns = split_names(o.y);
  if (columns.empty()) throw std::invalid_argument("--y: name at least one column");
  const auto x = table.numbers(o.x);
  if (x.empty()) throw std::invalid_argument(o.csv + ": no rows to plot");
  std::vector<plot::LineSeries> series;
  for (const auto& c : columns) series.push_back({c, x, table.numbers(c)});
  const std::string title = o.title.empty() ? o.csv : o.title;
  try {
    plot::line_chart({title, o.x, o.log_y ? o.y + " (log scale)" : o.y}, series, o.log_y).save_png(o.out);
  } catch (const std::invalid_argument& e) {  // names a series, not the file it came from
    throw std::invalid_argument(o.csv + ": " + e.what());
  }
  std::printf("wrote %s: %zu series, %d points each\n", o.out.c_str(), series.size(), table.rows());
}

struct TsneCommandOptions {
  std::string embeddings, out, color = "achieved_speed", coords_out;
  bool training_only = false;
  eval::TsneOptions tsne;
};

// The rows of the embedding table to map: all, or those with held_out = 0.
std::vector<int> selected_rows(const plot::CsvTable& table, bool training_only) {
  std::vector<int> rows;
  const auto held_out = training_only ? table.numbers("held_out") : std::vector<double>(table.rows(), 0);
  for (int r = 0; r < table.rows(); ++r)
    if (held_out[r] == 0) rows.push_back(r);
  return rows;
}

std::vector<std::string> latent_columns(const plot::CsvTable& table, const std::string& where) {
  std::vector<std::string> names;
  while (table.has_column("mu_" + std::to_string(names.size())))
    names.push_back("mu_" + std::to_string(names.size()));
  if (names.empty()) throw std::invalid_argument(where + ": no latent columns mu_0, mu_1, ...");
  return names;
}

// The input's descriptive columns (not mu_*/sigma_*) of the mapped rows, then tsne_x, tsne_y.
std::string coordinates_csv(const plot::CsvTable& table, const std::vector<int>& rows,
                            const std::vector<double>& embedding) {
  std::vector<std::string> kept;
  for (const auto& c : table.columns())
    if (c.rfind("mu_", 0) != 0 && c.rfind("sigma_", 0) != 0) kept.push_back(c);
  std::vector<std::vector<std::string>> cells;
  for (const auto& c : kept) cells.push_back(table.strings(c));
  std::string out;
  for (const auto& c : kept) out += c + ",";
  out += "tsne_x,tsne_y\n";
  char buf[64];
  for (size_t i = 0; i < rows.size(); ++i) {
    for (const auto& column : cells) out += column[rows[i]] + ",";
    std::snprintf(buf, sizeof buf, "%.9g,%.9g\n", embedding[2 * i], embedding[2 * i + 1]);
    out += buf;
  }
  return out;
}

void run_tsne(const TsneCommandOptions& o) {
  const auto table = plot::CsvTable::read(o.embeddings);
  const auto rows = selected_rows(table, o.training_only);
  const auto latents = latent_columns(table, o.embeddings);
  const auto colour_values = table.numbers(o.color);
  const int n = static_cast<int>(rows.size()), d = static_cast<int>(latents.size());
  std::vector<double> data(static_cast<size_t>(n) * d);
  for (int k = 0; k < d; ++k) {
    const auto column = table.numbers(latents[k]);
    for (int i = 0; i < n; ++i) data[static_cast<size_t>(i) * d + k] = column[rows[i]];
  }
  std::vector<double> x(n), y(n), value(n);
  const auto result = eval::tsne(data, n, d, o.tsne);
  for (int i = 0; i < n; ++i) {
    x[i] = result.embedding[2 * i];
    y[i] = result.embedding[2 * i + 1];
    value[i] = colour_values[rows[i]];
  }
  char title[128];
  std::snprintf(title, sizeof title, "t-SNE of %d embeddings (perplexity %g)", n, o.tsne.perplexity);
  const auto canvas = plot::scatter_chart({title, "t-SNE 1", "t-SNE 2"}, x, y, value, o.color);
  if (!o.coords_out.empty()) write_file_atomically(o.coords_out, coordinates_csv(table, rows, result.embedding));
  canvas.save_png(o.out);
  std::printf("wrote %s: %d points of %d dimensions, KL(P||Q) %.4f\n", o.out.c_str(), n, d,
              result.kl_divergence);
  if (!o.coords_out.empty()) std::printf("wrote %s\n", o.coords_out.c_str());
}

struct HistogramOptions {
  std::string csv, column, group_by, out, title;
  int bins = 40;
};

// Groups in numeric order when every group name is a number (target speeds), else by name.
std::vector<plot::HistogramSeries> grouped(const std::vector<double>& values,
                                           const std::vector<std::string>& groups,
                                           const std::string& group_column) {
  std::map<std::string, std::vector<double>> by_group;
  for (size_t i = 0; i < values.size(); ++i) by_group[groups[i]].push_back(values[i]);
  std::vector<std::pair<std::string, std::vector<double>>> ordered(by_group.begin(), by_group.end());
  auto number = [](const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    return (!s.empty() && *end == '\0') ? v : NAN;
  };
  const bool numeric = std::all_of(ordered.begin(), ordered.end(),
                                   [&](const auto& g) { return !std::isnan(number(g.first)); });
  if (numeric)
    std::sort(ordered.begin(), ordered.end(),
              [&](const auto& a, const auto& b) { return number(a.first) < number(b.first); });
  std::vector<plot::HistogramSeries> series;
  for (auto& [name, group_values] : ordered)
    series.push_back({group_column + " " + name, std::move(group_values)});
  return series;
}

void run_histogram(const HistogramOptions& o) {
  const auto table = plot::CsvTable::read(o.csv);
  const auto values = table.numbers(o.column);
  if (values.empty()) throw std::invalid_argument(o.csv + ": no rows to plot");
  const auto series = o.group_by.empty()
                          ? std::vector<plot::HistogramSeries>{{"", values}}
                          : grouped(values, table.strings(o.group_by), o.group_by);
  const auto edges = plot::even_bin_edges(series, o.bins);
  const std::string title = o.title.empty() ? "distribution of " + o.column : o.title;
  const auto canvas = plot::histogram_chart({title, o.column, "count"}, edges, series);
  std::fputs(plot::histogram_table(edges, series).c_str(), stdout);
  canvas.save_png(o.out);
  std::printf("wrote %s: %d values in %zu series\n", o.out.c_str(), table.rows(), series.size());
}

}  // namespace

void add_plot_commands(CLI::App& app) {
  CLI::App* plot = app.add_subcommand("plot", "draw PNG figures from metrics and embedding CSV files");
  plot->require_subcommand(1);

  auto curves = std::make_shared<CurvesOptions>();
  CLI::App* curves_cmd = plot->add_subcommand("curves", "line chart of CSV columns, e.g. training curves");
  curves_cmd->add_option("--csv", curves->csv, "CSV with a header row (e.g. run/metrics.csv)")->required();
  curves_cmd->add_option("--x", curves->x, "column on the x axis")->capture_default_str();
  curves_cmd->add_option("--y", curves->y, "comma-separated columns to draw")->required();
  curves_cmd->add_option("--out", curves->out, "PNG to write")->required();
  curves_cmd->add_flag("--log-y", curves->log_y, "logarithmic y axis (values must be positive)");
  curves_cmd->add_option("--title", curves->title, "figure title (default: the CSV path)");
  curves_cmd->callback([curves] { run_curves(*curves); });

  auto tsne = std::make_shared<TsneCommandOptions>();
  CLI::App* tsne_cmd = plot->add_subcommand(
      "tsne", "t-SNE of VAE embeddings (vaegail vae embed), coloured by a column (paper Fig. 4 left)");
  tsne_cmd->add_option("--embeddings", tsne->embeddings, "embedding CSV (episode,...,mu_*,sigma_*)")->required();
  tsne_cmd->add_option("--out", tsne->out, "PNG to write")->required();
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
  histogram_cmd->add_option("--out", histogram->out, "PNG to write")->required();
  histogram_cmd->add_option("--title", histogram->title, "figure title");
  histogram_cmd->callback([histogram] { run_histogram(*histogram); });
}

}  // namespace vaegail::cli
