// Figures are drawn by the matplotlib scripts under scripts/plot/ (one per kind of figure; see
// docs/architecture.md for why): a command writes the figure's data as CSV, then runs
// `python3 SCRIPT.py --csv DATA.csv ... --out FIGURE.png`. The binary carries a copy of every
// script (compiled in from scripts/plot/), so it runs without the source tree.
//
// The interpreter is $VAEGAIL_PYTHON when set; else the first of `python3` on PATH and Debian's
// /usr/bin/python3 (which a pyenv or venv python3 on PATH may hide) that imports matplotlib.
#pragma once

#include <string>
#include <vector>

#include "util/histogram.h"

namespace vaegail::cli {

// Whether some python3 imports matplotlib (checked once per process).
bool plotting_available();

// For commands whose main output is a figure: throws std::runtime_error of one line naming
// `what` and the package to install when no python3 imports matplotlib.
void require_plotting(const std::string& what);

// Runs scripts/plot/`script` (e.g. "curves.py") with `args`; the script writes the figure whole
// or not at all. Throws std::runtime_error of one line (the script's own error) when it fails,
// or when plotting is not available.
void draw_figure(const std::string& script, const std::vector<std::string>& args);

// For commands whose figures come beside their main output (tables, CSV): draws when matplotlib
// is there; else returns false, after a one-line warning naming the package (once per process).
bool draw_figure_if_possible(const std::string& script, const std::vector<std::string>& args);

// The file beside `figure` that holds its data: FIGURE without its extension, then ".csv".
std::string figure_data_path(const std::string& figure);

struct FigureLabels {
  std::string title, x, y;
};
// Overlaid histograms of `series` on `bins` equal bins: writes the values to
// figure_data_path(figure) (util/histogram.h's histogram_csv), then draws `figure` from it when
// matplotlib is there (draw_figure_if_possible). Returns whether the figure was drawn.
bool save_histogram_figure(const std::string& figure, const std::vector<HistogramSeries>& series, int bins,
                           const FigureLabels& labels);

}  // namespace vaegail::cli
