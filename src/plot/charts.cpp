#include "plot/charts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace vaegail::plot {
namespace {

constexpr int kTextScale = 2;
constexpr int kTitleScale = 3;
constexpr int kPad = 12;
constexpr int kTickLength = 5;
constexpr Rgb kGrid{225, 225, 225};
constexpr Rgb kFrame{60, 60, 60};
constexpr Rgb kInk{30, 30, 30};

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void include(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return lo > hi; }
};

// An empty or zero-width range widened so that it can be drawn.
Range drawable(Range r) {
  if (r.empty()) return {0, 1};
  if (r.hi > r.lo) return r;
  const double half = r.lo == 0 ? 0.5 : std::abs(r.lo) * 0.1;
  return {r.lo - half, r.hi + half};
}

Range padded(Range r, double fraction) {
  r = drawable(r);
  const double pad = (r.hi - r.lo) * fraction;
  return {r.lo - pad, r.hi + pad};
}

// One axis in display coordinates: the data itself, or its log10 on a log axis.
struct Axis {
  Range range;
  std::vector<double> ticks;
  std::vector<std::string> labels;
};

Axis linear_axis(Range range) {
  Axis axis{range, nice_ticks(range.lo, range.hi), {}};
  const double step = axis.ticks.size() > 1 ? axis.ticks[1] - axis.ticks[0] : range.hi - range.lo;
  for (double t : axis.ticks) axis.labels.push_back(tick_label(t, step));
  return axis;
}

std::string general_label(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

// Ticks at powers of ten when the range spans several decades, else at 1, 2 and 5 times them,
// else (a range within one such gap) at round linear values.
Axis log_axis(Range log_range) {
  Axis axis{log_range, {}, {}};
  auto add_candidates = [&](const std::vector<double>& mantissas) {
    axis.ticks.clear();
    axis.labels.clear();
    for (int k = static_cast<int>(std::floor(log_range.lo)); k <= static_cast<int>(std::ceil(log_range.hi)); ++k)
      for (double m : mantissas) {
        const double t = k + std::log10(m);
        if (t < log_range.lo - 1e-12 || t > log_range.hi + 1e-12) continue;
        axis.ticks.push_back(t);
        axis.labels.push_back(general_label(m * std::pow(10.0, k)));
      }
  };
  add_candidates({1});
  if (axis.ticks.size() >= 3) {
    // Keep at most about eight decades labelled.
    const size_t stride = (axis.ticks.size() + 7) / 8;
    Axis thinned{log_range, {}, {}};
    for (size_t i = 0; i < axis.ticks.size(); i += stride) {
      thinned.ticks.push_back(axis.ticks[i]);
      thinned.labels.push_back(axis.labels[i]);
    }
    return thinned;
  }
  add_candidates({1, 2, 5});
  if (axis.ticks.size() >= 2) return axis;
  const double lo = std::pow(10.0, log_range.lo), hi = std::pow(10.0, log_range.hi);
  const auto linear = nice_ticks(lo, hi);
  const double step = linear.size() > 1 ? linear[1] - linear[0] : hi - lo;
  axis.ticks.clear();
  axis.labels.clear();
  for (double t : linear) {
    if (t <= 0) continue;
    axis.ticks.push_back(std::log10(t));
    axis.labels.push_back(tick_label(t, step));
  }
  return axis;
}

int widest(const std::vector<std::string>& texts, int scale) {
  int w = 0;
  for (const auto& t : texts) w = std::max(w, text_width(t, scale));
  return w;
}

void require_finite(const std::vector<double>& values, const std::string& what) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw std::invalid_argument(what + ": value " + std::to_string(i) + " is not finite");
}

// The coordinates of one series: equally many, at least one, all finite.
void require_points(const std::vector<double>& x, const std::vector<double>& y, const std::string& what) {
  if (x.size() != y.size())
    throw std::invalid_argument(what + ": x has " + std::to_string(x.size()) + " values, y has " +
                                std::to_string(y.size()));
  if (x.empty()) throw std::invalid_argument(what + ": no points");
  require_finite(x, what + " x");
  require_finite(y, what + " y");
}

std::string series_name(const std::string& name, size_t index) {
  return name.empty() ? "series " + std::to_string(index) : "series '" + name + "'";
}

// The plot area of a chart and the mapping of display coordinates into it. Constructing one
// lays out the margins and draws the title, axis labels, grid and tick labels; finish() draws
// the frame over the data.
class Axes {
 public:
  // extra_right: pixels kept free right of the plot area (a colour bar). equal_aspect widens
  // one range so a unit is as long on x as on y.
  Axes(Canvas& canvas, const Labels& labels, Axis x, Axis y, int extra_right = 0,
       bool equal_aspect = false)
      : canvas_(canvas), x_(std::move(x)), y_(std::move(y)) {
    const int label_height = text_height(kTextScale);
    // One character of slack: equal_aspect may relabel the y axis after the margin is fixed.
    const int y_tick_width = widest(y_.labels, kTextScale) + text_width("0", kTextScale);
    left_ = kPad + (labels.y.empty() ? 0 : label_height + kPad) + y_tick_width + kTickLength + 4;
    top_ = top_margin(labels);
    right_ = canvas.width() - kPad - extra_right - text_width("00", kTextScale);
    bottom_ = top_ + plot_height(canvas.height(), labels);
    if (right_ - left_ < 40 || bottom_ - top_ < 40)
      throw std::invalid_argument("chart: canvas " + std::to_string(canvas.width()) + "x" +
                                  std::to_string(canvas.height()) + " is too small");
    if (equal_aspect) equalize_units();
    draw_texts(labels);
    draw_grid_and_ticks();
  }

  // The plot area's height does not depend on the data, so a chart can plan room in it.
  static int plot_height(int canvas_height, const Labels& labels) {
    const int label_height = text_height(kTextScale);
    const int bottom_margin = kPad + (labels.x.empty() ? 0 : label_height + kPad) + label_height + kTickLength + 6;
    return canvas_height - top_margin(labels) - bottom_margin;
  }

  Point to_pixel(double x, double y) const {
    return {left_ + (x - x_.range.lo) / (x_.range.hi - x_.range.lo) * (right_ - left_),
            bottom_ - (y - y_.range.lo) / (y_.range.hi - y_.range.lo) * (bottom_ - top_)};
  }
  double left() const { return left_; }
  double right() const { return right_; }
  double top() const { return top_; }
  double bottom() const { return bottom_; }

  void finish() { canvas_.draw_rect_outline(left_, top_, right_ + 1, bottom_ + 1, kFrame); }

 private:
  static int top_margin(const Labels& labels) {
    return kPad + (labels.title.empty() ? 0 : text_height(kTitleScale) + kPad) + 4;
  }

  // Only for linear axes: the ranges are widened in data units.
  void equalize_units() {
    const double ux = (x_.range.hi - x_.range.lo) / (right_ - left_);
    const double uy = (y_.range.hi - y_.range.lo) / (bottom_ - top_);
    auto widen = [](Range r, double span) {
      const double mid = (r.lo + r.hi) / 2;
      return Range{mid - span / 2, mid + span / 2};
    };
    if (ux < uy) x_ = linear_axis(widen(x_.range, uy * (right_ - left_)));
    if (uy < ux) y_ = linear_axis(widen(y_.range, ux * (bottom_ - top_)));
  }

  void draw_texts(const Labels& labels) {
    const double centre_x = (left_ + right_) / 2;
    if (!labels.title.empty()) draw_title(labels.title, centre_x);
    if (!labels.x.empty())
      canvas_.draw_text(centre_x, canvas_.height() - kPad, labels.x, kInk, kTextScale,
                        Align::Center, Align::End);
    if (!labels.y.empty())
      canvas_.draw_text_upwards(kPad, (top_ + bottom_) / 2, labels.y, kInk, kTextScale,
                                Align::Start, Align::Center);
  }

  // A title too wide for the canvas at the title scale is drawn smaller, and one wider than
  // the plot area is centred on the canvas instead, so that no title is cut at the edges.
  void draw_title(const std::string& title, double centre_x) {
    const int room = canvas_.width() - 2 * kPad;
    int scale = kTitleScale;
    while (scale > 1 && text_width(title, scale) > room) --scale;
    const double half = text_width(title, scale) / 2.0;
    const double x = half * 2 > room ? canvas_.width() / 2.0
                                     : std::clamp(centre_x, kPad + half, canvas_.width() - kPad - half);
    canvas_.draw_text(x, kPad, title, kInk, scale, Align::Center);
  }

  void draw_grid_and_ticks() {
    for (size_t i = 0; i < x_.ticks.size(); ++i) {
      const double px = std::round(to_pixel(x_.ticks[i], 0)[0]);
      canvas_.fill_rect(px, top_, px + 1, bottom_, kGrid);
      canvas_.fill_rect(px, bottom_, px + 1, bottom_ + kTickLength, kFrame);
      canvas_.draw_text(px + 0.5, bottom_ + kTickLength + 4, x_.labels[i], kInk, kTextScale,
                        Align::Center);
    }
    for (size_t i = 0; i < y_.ticks.size(); ++i) {
      const double py = std::round(to_pixel(0, y_.ticks[i])[1]);
      canvas_.fill_rect(left_, py, right_, py + 1, kGrid);
      canvas_.fill_rect(left_ - kTickLength, py, left_, py + 1, kFrame);
      canvas_.draw_text(left_ - kTickLength - 4, py + 0.5, y_.labels[i], kInk, kTextScale,
                        Align::End, Align::Center);
    }
  }

  Canvas& canvas_;
  Axis x_, y_;
  double left_ = 0, top_ = 0, right_ = 0, bottom_ = 0;
};

enum class Swatch { Box, Line, DashedLine };

struct LegendEntry {
  std::string name;
  Rgb color;
  Swatch swatch;
};

constexpr double kDash = 8;
int legend_row_height() { return text_height(kTextScale) + 8; }
double legend_height(size_t entries) { return 6.0 + legend_row_height() * static_cast<double>(entries); }

// Pixels in the box that hold something other than background or grid: what a legend placed
// there would hide.
int inked_pixels(const Canvas& canvas, double left, double top, double right, double bottom) {
  int count = 0;
  for (int y = std::max(0, static_cast<int>(top)); y < std::min(canvas.height(), static_cast<int>(bottom)); ++y)
    for (int x = std::max(0, static_cast<int>(left)); x < std::min(canvas.width(), static_cast<int>(right)); ++x) {
      const Rgb p = canvas.pixel(x, y);
      count += p != kWhite && p != kGrid;
    }
  return count;
}

// A boxed list in the corner of the plot area where it hides the least of the data; entries
// without a name are left out.
void draw_legend(Canvas& canvas, const Axes& axes, const std::vector<LegendEntry>& all) {
  std::vector<LegendEntry> entries;
  for (const auto& e : all)
    if (!e.name.empty()) entries.push_back(e);
  if (entries.empty()) return;
  const int row = legend_row_height(), swatch = 28;
  int text = 0;
  for (const auto& e : entries) text = std::max(text, text_width(e.name, kTextScale));
  const double width = 8 + swatch + 8 + text + 8, height = legend_height(entries.size());
  double left = 0, top = 0;
  int least = -1;
  // Corners in order of preference; the first of equally good ones wins.
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {axes.right() - 8 - width, axes.top() + 8},
           {axes.left() + 9, axes.top() + 8},
           {axes.right() - 8 - width, axes.bottom() - 8 - height},
           {axes.left() + 9, axes.bottom() - 8 - height}}) {
    const int hidden = inked_pixels(canvas, x, y, x + width, y + height);
    if (least < 0 || hidden < least) least = hidden, left = x, top = y;
  }
  const double right = left + width, bottom = top + height;
  canvas.fill_rect(left, top, right, bottom, kWhite, 0.85);
  canvas.draw_rect_outline(left, top, right, bottom, kGrid);
  for (size_t i = 0; i < entries.size(); ++i) {
    const double mid = top + 3 + row * (i + 0.5);
    const double x0 = left + 8, x1 = x0 + swatch;
    const auto& e = entries[i];
    if (e.swatch == Swatch::Box) {
      canvas.fill_rect(x0, mid - 6, x1, mid + 6, e.color, 0.6);
    } else {
      canvas.draw_polyline({{x0, mid}, {x1, mid}}, e.color, 2.5,
                           e.swatch == Swatch::DashedLine ? kDash * 0.75 : 0.0);
    }
    canvas.draw_text(x1 + 8, mid, e.name, kInk, kTextScale, Align::Start, Align::Center);
  }
}

std::vector<double> log10_of(const std::vector<double>& values, const std::string& what) {
  std::vector<double> out;
  for (size_t i = 0; i < values.size(); ++i) {
    if (!(values[i] > 0))
      throw std::invalid_argument(what + ": value " + std::to_string(i) + " is " +
                                  general_label(values[i]) + ", a log axis needs positive values");
    out.push_back(std::log10(values[i]));
  }
  return out;
}

std::vector<Point> pixels(const Axes& axes, const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<Point> points;
  for (size_t i = 0; i < x.size(); ++i) points.push_back(axes.to_pixel(x[i], y[i]));
  return points;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, target - 1);
  const int exponent = static_cast<int>(std::floor(std::log10(raw)));
  const double fraction = raw / std::pow(10.0, exponent);
  // The nearest of 1, 2, 5, 10 (roughly, in log terms) to the raw step.
  const double mantissa = fraction < 1.5 ? 1 : fraction < 3 ? 2 : fraction < 7 ? 5 : 10;
  // A tick k * mantissa * 10^exponent is formed with one rounding (k * mantissa is an exact
  // integer and so is 10^|exponent|), so 3 * 0.2 prints as 0.6, not 0.6000000000000001.
  const double power = std::pow(10.0, std::abs(exponent));
  auto tick = [&](double k) { return exponent >= 0 ? k * mantissa * power : k * mantissa / power; };
  const double step = tick(1);
  const double slack = step * 1e-9;
  std::vector<double> ticks;
  for (double k = std::ceil((lo - slack) / step); tick(k) <= hi + slack; ++k)
    ticks.push_back(k == 0 ? 0.0 : tick(k));
  return ticks;
}

std::string tick_label(double value, double step) {
  char buf[48];
  const int decimals =
      step > 0 ? std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9))) : 0;
  if (std::abs(value) >= 1e6 || decimals > 4) {
    std::snprintf(buf, sizeof buf, "%g", value);
  } else {
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    if (std::string(buf).find_first_not_of("-0.") == std::string::npos)
      std::snprintf(buf, sizeof buf, "%.*f", decimals, 0.0);  // no "-0"
  }
  return buf;
}

Rgb viridis(double t) {
  // Samples of matplotlib's viridis at t = 0, 1/8, ..., 1, interpolated linearly.
  static constexpr std::array<Rgb, 9> kStops{{{68, 1, 84},
                                              {71, 44, 122},
                                              {59, 81, 139},
                                              {44, 113, 142},
                                              {33, 144, 141},
                                              {39, 173, 129},
                                              {92, 200, 99},
                                              {170, 220, 50},
                                              {253, 231, 37}}};
  const double s = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (kStops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(s), kStops.size() - 2);
  const double f = s - i;
  auto channel = [f](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + f * (b - a)));
  };
  const Rgb a = kStops[i], b = kStops[i + 1];
  return {channel(a.r, b.r), channel(a.g, b.g), channel(a.b, b.b)};
}

std::vector<Rgb> series_colors(int n) {
  // matplotlib's "tab10".
  static const std::vector<Rgb> kPalette{{31, 119, 180}, {255, 127, 14}, {44, 160, 44},
                                         {214, 39, 40},  {148, 103, 189}, {140, 86, 75},
                                         {227, 119, 194}, {127, 127, 127}, {188, 189, 34},
                                         {23, 190, 207}};
  if (n <= static_cast<int>(kPalette.size()))
    return {kPalette.begin(), kPalette.begin() + std::max(0, n)};
  std::vector<Rgb> colors;
  // Viridis' yellow end is hard to see on white; stop short of it.
  for (int i = 0; i < n; ++i) colors.push_back(viridis(0.9 * i / (n - 1)));
  return colors;
}

std::vector<double> even_bin_edges(double lo, double hi, int bins) {
  if (bins < 1) throw std::invalid_argument("histogram: bins must be >= 1, got " + std::to_string(bins));
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo)
    throw std::invalid_argument("histogram: bad range [" + general_label(lo) + ", " + general_label(hi) + "]");
  const Range r = drawable({lo, hi});
  std::vector<double> edges;
  for (int i = 0; i <= bins; ++i) edges.push_back(r.lo + (r.hi - r.lo) * i / bins);
  return edges;
}

std::vector<double> even_bin_edges(const std::vector<HistogramSeries>& series, int bins) {
  Range r;
  for (const auto& s : series)
    for (double v : s.values) r.include(v);
  if (r.empty()) throw std::invalid_argument("histogram: no values to bin");
  return even_bin_edges(r.lo, r.hi, bins);
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
    char buf[64];
    const bool last = b + 2 == bin_edges.size();
    std::snprintf(buf, sizeof buf, "[%.4g, %.4g%c", bin_edges[b], bin_edges[b + 1], last ? ']' : ')');
    bins.push_back(buf);
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

Canvas histogram_chart(const Labels& labels, const std::vector<double>& bin_edges,
                       const std::vector<HistogramSeries>& series, Size size) {
  if (series.empty()) throw std::invalid_argument("histogram: no series to draw");
  std::vector<std::vector<long>> counts;
  long most = 1;
  for (size_t s = 0; s < series.size(); ++s) {
    require_finite(series[s].values, "histogram " + series_name(series[s].name, s));
    counts.push_back(bin_counts(series[s].values, bin_edges));
    for (long c : counts.back()) most = std::max(most, c);
  }
  // Bars fill the plot area's corners more often than curves do: leave room above them for
  // the legend.
  const size_t named = std::count_if(series.begin(), series.end(), [](const auto& s) { return !s.name.empty(); });
  const double legend_share =
      named == 0 ? 0.0 : (legend_height(named) + 16) / Axes::plot_height(size.height, labels);
  Canvas canvas(size.width, size.height);
  Axes axes(canvas, labels, linear_axis({bin_edges.front(), bin_edges.back()}),
            linear_axis({0, most * 1.05 / std::max(0.3, 1 - legend_share)}));
  const auto colors = series_colors(static_cast<int>(series.size()));
  // One distribution can be opaque; overlaid ones must let each other show through.
  const double alpha = series.size() == 1 ? 0.8 : 0.4;
  std::vector<LegendEntry> legend;
  for (size_t s = 0; s < series.size(); ++s) {
    std::vector<Point> outline{axes.to_pixel(bin_edges.front(), 0)};
    for (size_t b = 0; b < counts[s].size(); ++b) {
      const Point low = axes.to_pixel(bin_edges[b], 0);
      const Point high = axes.to_pixel(bin_edges[b + 1], static_cast<double>(counts[s][b]));
      if (counts[s][b] > 0) canvas.fill_rect(low[0], high[1], high[0], low[1], colors[s], alpha);
      outline.push_back({low[0], high[1]});
      outline.push_back(high);
    }
    outline.push_back(axes.to_pixel(bin_edges.back(), 0));
    canvas.draw_polyline(outline, colors[s], 1.5);
    legend.push_back({series[s].name, colors[s], Swatch::Box});
  }
  axes.finish();
  draw_legend(canvas, axes, legend);
  return canvas;
}

Canvas scatter_chart(const Labels& labels, const std::vector<double>& x, const std::vector<double>& y,
                     const std::vector<double>& value, const std::string& value_label, Size size) {
  require_points(x, y, "scatter");
  if (value.size() != x.size())
    throw std::invalid_argument("scatter: " + std::to_string(x.size()) + " points but " +
                                std::to_string(value.size()) + " colour values");
  require_finite(value, "scatter colour value");
  Range rx, ry, rv;
  for (size_t i = 0; i < x.size(); ++i) {
    rx.include(x[i]);
    ry.include(y[i]);
    rv.include(value[i]);
  }
  const Axis bar = linear_axis(drawable(rv));
  constexpr int kBarWidth = 22;
  const int label_height = text_height(kTextScale);
  const int bar_space = kPad + kBarWidth + kTickLength + 4 + widest(bar.labels, kTextScale) +
                        (value_label.empty() ? 0 : kPad + label_height) + kPad;
  Canvas canvas(size.width, size.height);
  Axes axes(canvas, labels, linear_axis(padded(rx, 0.04)), linear_axis(padded(ry, 0.04)), bar_space);
  const double span = bar.range.hi - bar.range.lo;
  for (size_t i = 0; i < x.size(); ++i)
    canvas.fill_circle(axes.to_pixel(x[i], y[i]), 4.0, viridis((value[i] - bar.range.lo) / span));
  axes.finish();

  const double bar_left = canvas.width() - bar_space + kPad, bar_right = bar_left + kBarWidth;
  const double top = axes.top(), bottom = axes.bottom();
  auto bar_y = [&](double v) { return bottom - (v - bar.range.lo) / span * (bottom - top); };
  for (int py = static_cast<int>(top); py < static_cast<int>(bottom); ++py)
    canvas.fill_rect(bar_left, py, bar_right, py + 1, viridis((bottom - (py + 0.5)) / (bottom - top)));
  canvas.draw_rect_outline(bar_left, top, bar_right, bottom, kFrame);
  for (size_t i = 0; i < bar.ticks.size(); ++i) {
    const double py = std::round(bar_y(bar.ticks[i]));
    canvas.fill_rect(bar_right, py, bar_right + kTickLength, py + 1, kFrame);
    canvas.draw_text(bar_right + kTickLength + 4, py + 0.5, bar.labels[i], kInk, kTextScale,
                     Align::Start, Align::Center);
  }
  if (!value_label.empty())
    canvas.draw_text_upwards(canvas.width() - kPad - label_height, (top + bottom) / 2, value_label,
                             kInk, kTextScale, Align::Start, Align::Center);
  return canvas;
}

Canvas line_chart(const Labels& labels, const std::vector<LineSeries>& series, bool log_y, Size size) {
  if (series.empty()) throw std::invalid_argument("line chart: no series to draw");
  std::vector<std::vector<double>> ys;
  Range rx, ry;
  for (size_t s = 0; s < series.size(); ++s) {
    const std::string what = "line chart " + series_name(series[s].name, s);
    require_points(series[s].x, series[s].y, what);
    ys.push_back(log_y ? log10_of(series[s].y, what + " y") : series[s].y);
    for (double v : series[s].x) rx.include(v);
    for (double v : ys.back()) ry.include(v);
  }
  Canvas canvas(size.width, size.height);
  const Range y_range = padded(ry, 0.05);
  Axes axes(canvas, labels, linear_axis(drawable(rx)), log_y ? log_axis(y_range) : linear_axis(y_range));
  const auto colors = series_colors(static_cast<int>(series.size()));
  std::vector<LegendEntry> legend;
  for (size_t s = 0; s < series.size(); ++s) {
    const auto points = pixels(axes, series[s].x, ys[s]);
    canvas.draw_polyline(points, colors[s], 2.0);
    if (points.size() == 1) canvas.fill_circle(points[0], 3.0, colors[s]);
    legend.push_back({series[s].name, colors[s], Swatch::Line});
  }
  axes.finish();
  draw_legend(canvas, axes, legend);
  return canvas;
}

Canvas path_chart(const Labels& labels, const std::vector<PathSeries>& paths, Size size) {
  if (paths.empty()) throw std::invalid_argument("path chart: no paths to draw");
  Range rx, ry;
  for (size_t s = 0; s < paths.size(); ++s) {
    const std::string what = "path chart " + series_name(paths[s].name, s);
    require_points(paths[s].x, paths[s].y, what);
    for (double v : paths[s].x) rx.include(v);
    for (double v : paths[s].y) ry.include(v);
  }
  Canvas canvas(size.width, size.height);
  Axes axes(canvas, labels, linear_axis(padded(rx, 0.06)), linear_axis(padded(ry, 0.06)), 0,
            /*equal_aspect=*/true);
  const auto palette = series_colors(static_cast<int>(paths.size()));
  std::vector<LegendEntry> legend;
  for (size_t s = 0; s < paths.size(); ++s) {
    const Rgb color = paths[s].color.value_or(palette[s]);
    const auto points = pixels(axes, paths[s].x, paths[s].y);
    canvas.draw_polyline(points, color, 2.0, paths[s].dashed ? kDash : 0.0);
    if (paths[s].mark_ends) {
      canvas.fill_circle(points.front(), 4.5, color);
      const Point end = points.back();
      canvas.fill_rect(end[0] - 4.5, end[1] - 4.5, end[0] + 4.5, end[1] + 4.5, color);
    }
    legend.push_back({paths[s].name, color, paths[s].dashed ? Swatch::DashedLine : Swatch::Line});
  }
  axes.finish();
  draw_legend(canvas, axes, legend);
  return canvas;
}

}  // namespace vaegail::plot
