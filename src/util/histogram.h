// Histogram counts as text, printed beside the figures scripts/plot/histogram.py draws from the
// same values: equal bins spanning all series, counted as numpy's histogram counts them (the
// bins the script uses too).
#pragma once

#include <string>
#include <vector>

namespace vaegail {

struct HistogramSeries {
  std::string name;
  std::vector<double> values;
};

// `bins` equal bins spanning [lo, hi]; lo == hi is widened by 10% of |lo| each side (0.5 at 0).
std::vector<double> even_bin_edges(double lo, double hi, int bins);
// `bins` equal bins spanning the values of all series.
std::vector<double> even_bin_edges(const std::vector<HistogramSeries>& series, int bins);
// Counts per bin [edges[i], edges[i+1]); the last bin also holds its right edge, as numpy's
// histogram does. Values outside the edges are not counted.
std::vector<long> bin_counts(const std::vector<double>& values, const std::vector<double>& edges);

// The counts as text: one row per bin ("[lo, hi)"), one column per series.
std::string histogram_table(const std::vector<double>& bin_edges, const std::vector<HistogramSeries>& series);

// The values in long form for the figure script: a header "series,value", then one row per
// value; a series name with a comma or quote is quoted as RFC 4180 says ("a=1, b=2").
std::string histogram_csv(const std::vector<HistogramSeries>& series);

}  // namespace vaegail
