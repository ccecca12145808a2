#include "plot/charts.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vaegail::plot {
namespace {

bool is_grey(Rgb p) { return p.r == p.g && p.g == p.b; }

TEST(NiceTicks, RoundValuesInsideTheRange) {
  EXPECT_EQ(nice_ticks(0, 1), (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  EXPECT_EQ(nice_ticks(0, 100), (std::vector<double>{0, 20, 40, 60, 80, 100}));
  EXPECT_EQ(nice_ticks(-3.2, 5.7), (std::vector<double>{-2, 0, 2, 4}));
  EXPECT_EQ(nice_ticks(0.013, 0.061), (std::vector<double>{0.02, 0.03, 0.04, 0.05, 0.06}));
  EXPECT_EQ(nice_ticks(1500, 9000, 4), (std::vector<double>{2000, 4000, 6000, 8000}));
  EXPECT_EQ(nice_ticks(2, 2), (std::vector<double>{2}));
  // Ticks are exact multiples of the step, with no "-0" near zero.
  for (double t : nice_ticks(-0.3, 0.3)) EXPECT_FALSE(t == 0 && std::signbit(t));
}

TEST(NiceTicks, LabelsUseTheDecimalsTheStepNeeds) {
  EXPECT_EQ(tick_label(0.4, 0.2), "0.4");
  EXPECT_EQ(tick_label(0.05, 0.01), "0.05");
  EXPECT_EQ(tick_label(40, 20), "40");
  EXPECT_EQ(tick_label(-1e-17, 0.5), "0.0");
  EXPECT_EQ(tick_label(2e7, 1e7), "2e+07");
}

TEST(Colors, ViridisRunsFromPurpleToYellowGettingBrighter) {
  EXPECT_EQ(viridis(0), (Rgb{68, 1, 84}));
  EXPECT_EQ(viridis(1), (Rgb{253, 231, 37}));
  EXPECT_EQ(viridis(-3), viridis(0));
  EXPECT_EQ(viridis(7), viridis(1));
  auto luma = [](Rgb c) { return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b; };
  for (int i = 1; i <= 100; ++i) EXPECT_GT(luma(viridis(i / 100.0)), luma(viridis((i - 1) / 100.0)));
}

TEST(Colors, SeriesColorsAreDistinct) {
  for (int n : {3, 10, 14}) {
    const auto colors = series_colors(n);
    ASSERT_EQ(colors.size(), static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < i; ++j) EXPECT_NE(colors[i], colors[j]);
  }
}

TEST(Histogram, CountsFollowNumpyBinning) {
  const auto edges = even_bin_edges(0, 4, 4);
  EXPECT_EQ(edges, (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(bin_counts({0, 0.5, 1, 3.999, 4, 4.01, -1}, edges), (std::vector<long>{2, 1, 0, 2}));
  EXPECT_THROW(bin_counts({1}, {0, 2, 1}), std::invalid_argument);
  EXPECT_EQ(even_bin_edges(3, 3, 1), (std::vector<double>{2.7, 3.3}));
  EXPECT_EQ(even_bin_edges({{"a", {1, 2}}, {"b", {-1}}}, 3), (std::vector<double>{-1, 0, 1, 2}));
  EXPECT_THROW(even_bin_edges({{"a", {}}}, 3), std::invalid_argument);
}

TEST(Histogram, TableListsCountsPerBinAndSeries) {
  EXPECT_EQ(histogram_table({0, 0.5, 1}, {{"slow", {0.1, 0.2, 1.0}}, {"", {0.7}}}),
            "bin         slow   count\n"
            "[0, 0.5)       2       0\n"
            "[0.5, 1]       1       1\n");
}

// Coloured (non-grey) pixels per column: histogram bars are the only colour without a legend.
std::vector<int> coloured_per_column(const Canvas& c) {
  std::vector<int> counts(c.width(), 0);
  for (int x = 0; x < c.width(); ++x)
    for (int y = 0; y < c.height(); ++y) counts[x] += !is_grey(c.pixel(x, y));
  return counts;
}

TEST(Histogram, BarsAppearWhereTheDataIs) {
  // 10 values in bin 0 and 20 in bin 2 of four: two bars of equal width, one bin apart, the
  // second twice as tall.
  std::vector<double> values(10, 0.5);
  values.insert(values.end(), 20, 2.5);
  const Canvas c = histogram_chart({"t", "x", "count"}, even_bin_edges(0, 4, 4), {{"", values}});
  const auto columns = coloured_per_column(c);
  // [first, last] columns of each run of tall columns; the grey frame may split a run.
  std::vector<std::pair<int, int>> runs;
  for (int x = 0; x < c.width(); ++x) {
    if (columns[x] < 20) continue;
    if (runs.empty() || runs.back().second < x - 2) runs.push_back({x, x});
    runs.back().second = x;
  }
  ASSERT_EQ(runs.size(), 2u);
  const int w1 = runs[0].second - runs[0].first + 1, w2 = runs[1].second - runs[1].first + 1;
  EXPECT_NEAR(w1, w2, 3);
  // Bins 0 and 2: centres two bar widths apart, the empty bin between them.
  EXPECT_NEAR((runs[1].first + runs[1].second) / 2.0 - (runs[0].first + runs[0].second) / 2.0, 2 * w2, 8);
  const int h1 = columns[(runs[0].first + runs[0].second) / 2];
  const int h2 = columns[(runs[1].first + runs[1].second) / 2];
  EXPECT_NEAR(static_cast<double>(h2) / h1, 2.0, 0.05);
}

TEST(Histogram, OverlaidSeriesBlendAndGetALegend) {
  const std::vector<double> a(5, 0.5), b(5, 0.5);
  const Canvas one = histogram_chart({}, {0, 1}, {{"a", a}});
  const Canvas two = histogram_chart({}, {0, 1}, {{"a", a}, {"b", b}});
  const int x = one.width() / 2, y = one.height() / 2;
  const auto colors = series_colors(2);
  // Where both bars lie, the second series shows through, tinted by the first.
  EXPECT_NE(two.pixel(x, y), colors[1]);
  EXPECT_NE(two.pixel(x, y), one.pixel(x, y));
  EXPECT_THROW(histogram_chart({}, {0, 1}, {}), std::invalid_argument);
  EXPECT_THROW(histogram_chart({}, {0, 1}, {{"bad", {NAN}}}), std::invalid_argument);
}

TEST(Scatter, PointsTakeTheirValuesColourAndTheBarSpansTheMap) {
  const Canvas c = scatter_chart({"", "x", "y"}, {0, 1}, {0, 1}, {0, 1}, "speed");
  bool low = false, high = false;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      low |= c.pixel(x, y) == viridis(0);
      high |= c.pixel(x, y) == viridis(1);
    }
  EXPECT_TRUE(low);
  EXPECT_TRUE(high);
  EXPECT_THROW(scatter_chart({}, {0, 1}, {0}, {0, 1}, ""), std::invalid_argument);
  EXPECT_THROW(scatter_chart({}, {0}, {0}, {0, 1}, ""), std::invalid_argument);
}

TEST(LineChart, LogAxisNeedsPositiveValues) {
  const LineSeries s{"loss", {0, 1, 2}, {10, 1, 0.1}};
  EXPECT_NO_THROW(line_chart({}, {s}, true));
  try {
    line_chart({}, {{"loss", {0, 1}, {1, 0}}}, true);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'loss'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(line_chart({}, {{"a", {0, 1}, {1}}}), std::invalid_argument);
}

TEST(LineChart, SeriesDrawnInPaletteOrder) {
  const Canvas c = line_chart({}, {{"", {0, 1}, {0, 0}}, {"", {0, 1}, {1, 1}}});
  const auto colors = series_colors(2);
  int first = 0, second = 0;
  for (int y = 0; y < c.height(); ++y) {
    first += c.pixel(c.width() / 2, y) == colors[0];
    second += c.pixel(c.width() / 2, y) == colors[1];
  }
  EXPECT_GE(first, 1);
  EXPECT_GE(second, 1);
}

TEST(Labels, ALongTitleShrinksToStayInsideTheCanvas) {
  const std::string title(70, 'W');  // about 1,400 pixels wide at the title scale
  const Canvas c = line_chart({title, "", ""}, {{"", {0, 1}, {0, 1}}});
  const Rgb background = c.pixel(0, 0);
  const int band = 40;  // the title's rows
  int inked = 0;
  for (int y = 0; y < band; ++y)
    for (int x = 0; x < c.width(); ++x) {
      const bool ink = !(c.pixel(x, y) == background);
      inked += ink;
      if (x < 4 || x >= c.width() - 4) EXPECT_FALSE(ink) << "title ink at column " << x;
    }
  EXPECT_GT(inked, 500);
}

TEST(PathChart, UsesGivenColoursAndKeepsUnitsEqual) {
  const Rgb red{220, 30, 30};
  // A unit square: with equal units its drawn width and height agree.
  const PathSeries square{"", {0, 1, 1, 0, 0}, {0, 0, 1, 1, 0}, red, false, false};
  const Canvas c = path_chart({}, {square}, {900, 500});
  int min_x = c.width(), max_x = -1, min_y = c.height(), max_y = -1;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x)
      if (c.pixel(x, y) == red) {
        min_x = std::min(min_x, x), max_x = std::max(max_x, x);
        min_y = std::min(min_y, y), max_y = std::max(max_y, y);
      }
  ASSERT_GE(max_x, 0);
  EXPECT_NEAR(max_x - min_x, max_y - min_y, 2);
  EXPECT_GT(max_y - min_y, 200);
}

}  // namespace
}  // namespace vaegail::plot
