// The paper's kinds of figure as functions from plain data to a Canvas (save it with
// Canvas::save_png): overlaid histograms, a scatter coloured by a value with a colour bar,
// line charts of training curves, and 2-D paths. Every chart has a title, axis labels with
// "nice" tick values, and a legend when its series are named.
//
// Charts throw std::invalid_argument on data they cannot draw (no points, x and y of different
// lengths, non-finite values, non-positive values on a log axis), naming the series.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "plot/canvas.h"

namespace vaegail::plot {

struct Labels {
  std::string title, x, y;
};

struct Size {
  int width = 960, height = 640;
};

// About `target` round tick values (1, 2 or 5 times a power of ten apart) inside [lo, hi].
std::vector<double> nice_ticks(double lo, double hi, int target = 6);
// `value` with as many decimals as the tick spacing `step` needs ("0.25", "-3", "1e+06").
std::string tick_label(double value, double step);

// A viridis-like map from t in [0, 1] (clamped) to colour: dark purple to yellow, brightness
// rising monotonically so the order survives grey-scale printing.
Rgb viridis(double t);
// Colours for n series: a qualitative palette, or viridis samples when there are more series
// than it has colours (series then are usually ordered, e.g. target speeds).
std::vector<Rgb> series_colors(int n);

// `bins` equal bins spanning [lo, hi] (lo == hi is widened by 0.5 each side).
std::vector<double> even_bin_edges(double lo, double hi, int bins);
struct HistogramSeries {
  std::string name;
  std::vector<double> values;
};
// `bins` equal bins spanning the values of all series.
std::vector<double> even_bin_edges(const std::vector<HistogramSeries>& series, int bins);
// Counts per bin [edges[i], edges[i+1]); the last bin also holds its right edge, as numpy's
// histogram does. Values outside the edges are not counted.
std::vector<long> bin_counts(const std::vector<double>& values, const std::vector<double>& edges);

// The same counts as text: one row per bin ("[lo, hi)"), one column per series.
std::string histogram_table(const std::vector<double>& bin_edges,
                            const std::vector<HistogramSeries>& series);
// Series are drawn over each other, semi-transparent, so overlapping distributions stay visible.
Canvas histogram_chart(const Labels& labels, const std::vector<double>& bin_edges,
                       const std::vector<HistogramSeries>& series, Size size = {});

// Point i at (x[i], y[i]) coloured by value[i] through viridis; the colour bar is titled
// `value_label`.
Canvas scatter_chart(const Labels& labels, const std::vector<double>& x, const std::vector<double>& y,
                     const std::vector<double>& value, const std::string& value_label,
                     Size size = {});

struct LineSeries {
  std::string name;
  std::vector<double> x, y;
};
Canvas line_chart(const Labels& labels, const std::vector<LineSeries>& series, bool log_y = false,
                  Size size = {});

struct PathSeries {
  std::string name;
  std::vector<double> x, y;
  std::optional<Rgb> color;  // default: series_colors
  bool dashed = false;
  bool mark_ends = true;  // a dot at the start, a square at the end
};
// Axes keep equal units on x and y, so shapes of paths are not distorted.
Canvas path_chart(const Labels& labels, const std::vector<PathSeries>& paths, Size size = {});

}  // namespace vaegail::plot
