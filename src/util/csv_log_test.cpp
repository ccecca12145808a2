#include "util/csv_log.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "util/atomic_file.h"

namespace vaegail {
namespace {

TEST(CsvLog, WritesHeaderOnceAndAppendsOnReopen) {
  const std::string path = (std::filesystem::temp_directory_path() / "vaegail_metrics.csv").string();
  std::remove(path.c_str());
  {
    CsvLog log(path, {"step", "loss"});
    log.write({1, 0.5});
  }
  {
    CsvLog log(path, {"step", "loss"});
    log.write({2, 0.25});
  }
  EXPECT_EQ(read_file(path), "step,loss\n1,0.5\n2,0.25\n");
  EXPECT_THROW(CsvLog(path, {"step", "other"}), std::runtime_error);
  CsvLog log(path, {"step", "loss"});
  EXPECT_THROW(log.write({1}), std::logic_error);
  std::remove(path.c_str());
}

TEST(SplitCsvLine, KeepsEmptyCellsIncludingATrailingOne) {
  EXPECT_EQ(split_csv_line("a,,b"), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_EQ(split_csv_line("1,2,"), (std::vector<std::string>{"1", "2", ""}));
  EXPECT_TRUE(split_csv_line("").empty());
}

}  // namespace
}  // namespace vaegail
