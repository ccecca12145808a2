#include "util/histogram.h"

#include <gtest/gtest.h>

namespace vaegail {
namespace {

TEST(Histogram, CountsFollowNumpyBinning) {
  const auto edges = even_bin_edges(0, 4, 4);
  EXPECT_EQ(edges, (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(bin_counts({0, 0.5, 1, 3.999, 4, 4.01, -1}, edges), (std::vector<long>{2, 1, 0, 2}));
  EXPECT_THROW(bin_counts({1}, {0, 2, 1}), std::invalid_argument);
  EXPECT_EQ(even_bin_edges(3, 3, 1), (std::vector<double>{2.7, 3.3}));
  EXPECT_EQ(even_bin_edges(0, 0, 1), (std::vector<double>{-0.5, 0.5}));
  EXPECT_EQ(even_bin_edges({{"a", {1, 2}}, {"b", {-1}}}, 3), (std::vector<double>{-1, 0, 1, 2}));
  EXPECT_THROW(even_bin_edges({{"a", {}}}, 3), std::invalid_argument);
  EXPECT_THROW(even_bin_edges(0, 1, 0), std::invalid_argument);
}

TEST(Histogram, TableListsCountsPerBinAndSeries) {
  EXPECT_EQ(histogram_table({0, 0.5, 1}, {{"slow", {0.1, 0.2, 1.0}}, {"", {0.7}}}),
            "bin         slow   count\n"
            "[0, 0.5)       2       0\n"
            "[0.5, 1]       1       1\n");
}

TEST(Histogram, CsvHasOneRowPerValueNamedBySeries) {
  EXPECT_EQ(histogram_csv({{"vae", {0.5, -1.25}}, {"bc", {3}}}), "series,value\nvae,0.5\nvae,-1.25\nbc,3\n");
  EXPECT_EQ(histogram_csv({{"a=1, b=\"2\"", {1}}}), "series,value\n\"a=1, b=\"\"2\"\"\",1\n");
}

}  // namespace
}  // namespace vaegail
