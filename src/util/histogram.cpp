#include "util/histogram.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace vaegail {
namespace {

std::string general_label(double value) { return fmt::format("{:g}", value); }

}  // namespace

std::vector<double> even_bin_edges(double lo, double hi, int bins) {
  if (bins < 1) throw std::invalid_argument("histogram: bins must be >= 1, got " + std::to_string(bins));
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo)
    throw std::invalid_argument("histogram: bad range [" + general_label(lo) + ", " + general_label(hi) + "]");
  if (lo == hi) {  // one value: a bin around it
    const double half = lo == 0 ? 0.5 : std::abs(lo) * 0.1;
    lo -= half;
    hi += half;
  }
  std::vector<double> edges;
  for (int i = 0; i <= bins; ++i) edges.push_back(lo + (hi - lo) * i / bins);
  return edges;
}

std::vector<double> even_bin_edges(const std::vector<HistogramSeries>& series, int bins) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& s : series)
    for (double v : s.values) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (lo > hi) throw std::invalid_argument("histogram: no values to bin");
  return even_bin_edges(lo, hi, bins);
}

std::vector<long> bin_counts(const std::vector<double>& values, const std::vector<double>& edges) {
  if (edges.size() < 2) throw std::invalid_argument("histogram: needs at least two bin edges");
  for (size_t i = 1; i < edges.size(); ++i)
    if (!(edges[i] > edges[i - 1]))
      throw std::invalid_argument("histogram: bin edges must increase, edge " + std::to_string(i) +
                                  " is " + general_label(edges[i]) + " after " + general_label(edges[i - 1]));
  std::vector<long> counts(edges.size() - 1, 0);
  for (double v : values) {
    if (!(v >= edges.front() && v <= edges.back())) continue;
    const auto upper = std::upper_bound(edges.begin(), edges.end(), v);
    const size_t bin = std::min(static_cast<size_t>(upper - edges.begin()) - 1, counts.size() - 1);
    ++counts[bin];
  }
  return counts;
}

std::string histogram_table(const std::vector<double>& bin_edges,
                            const std::vector<HistogramSeries>& series) {
  std::vector<std::vector<long>> counts;
  for (const auto& s : series) counts.push_back(bin_counts(s.values, bin_edges));
  std::vector<std::string> bins;
  for (size_t b = 0; b + 1 < bin_edges.size(); ++b) {
    const bool last = b + 2 == bin_edges.size();
    bins.push_back(fmt::format("[{:.4g}, {:.4g}{}", bin_edges[b], bin_edges[b + 1], last ? ']' : ')'));
  }
  size_t bin_width = 3;
  for (const auto& b : bins) bin_width = std::max(bin_width, b.size());
  auto padded_left = [](const std::string& text, size_t width) {
    return std::string(width > text.size() ? width - text.size() : 0, ' ') + text;
  };
  std::vector<size_t> widths;
  std::string out = "bin" + std::string(bin_width - 3, ' ');
  for (size_t s = 0; s < series.size(); ++s) {
    const std::string name = series[s].name.empty() ? "count" : series[s].name;
    widths.push_back(std::max<size_t>(name.size(), 6));
    out += "  " + padded_left(name, widths[s]);
  }
  out += "\n";
  for (size_t b = 0; b < bins.size(); ++b) {
    out += bins[b] + std::string(bin_width - bins[b].size(), ' ');
    for (size_t s = 0; s < series.size(); ++s)
      out += "  " + padded_left(std::to_string(counts[s][b]), widths[s]);
    out += "\n";
  }
  return out;
}

std::string histogram_csv(const std::vector<HistogramSeries>& series) {
  std::string out = "series,value\n";
  for (const auto& s : series) {
    std::string name = s.name;
    if (name.find_first_of(",\"\n") != std::string::npos) {
      name.clear();
      for (char c : s.name) name += c == '"' ? std::string("\"\"") : std::string(1, c);
      name = '"' + name + '"';
    }
    for (double v : s.values) out += fmt::format("{},{:.9g}\n", name, v);
  }
  return out;
}

}  // namespace vaegail
