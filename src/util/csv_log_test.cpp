#include "util/csv_log.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "util/atomic_file.h"
#include "util/test_error.h"
#include "util/test_small_fs.h"

namespace vaegail {
namespace {

std::string temp_csv(const std::string& name) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::remove(path.c_str());
  return path;
}

TEST(CsvLog, WritesHeaderOnceAndAppendsOnReopen) {
  const std::string path = temp_csv("vaegail_metrics.csv");
  {
    CsvLog log(path, {"step", "loss"});
    log.write({{"step", 1}, {"loss", 0.5}});
  }
  {
    CsvLog log(path, {"step", "loss"});
    log.write({{"step", 2}, {"loss", 0.25}});
  }
  EXPECT_EQ(read_file(path), "step,loss\n1,0.5\n2,0.25\n");
  EXPECT_THROW(CsvLog(path, {"step", "other"}), std::runtime_error);
  std::remove(path.c_str());
}

TEST(CsvLog, WritesValuesInTheColumnsOrderNotTheNames) {
  const std::string path = temp_csv("vaegail_metrics_order.csv");
  CsvLog(path, {"zeta", "alpha", "mid"}).write({{"alpha", 1}, {"mid", 2}, {"zeta", 3}});
  EXPECT_EQ(read_file(path), "zeta,alpha,mid\n3,1,2\n");
  std::remove(path.c_str());
}

// The message names the column; nothing of the bad row reaches the file.
void expect_rejected(CsvLog& log, const Metrics& row, const std::string& message) {
  try {
    log.write(row);
    ADD_FAILURE() << "no throw for " << message;
  } catch (const std::logic_error& e) {
    EXPECT_EQ(std::string(e.what()), log.path() + ": " + message);
  }
}

TEST(CsvLog, AMissingOrUnknownNameThrowsNamingIt) {
  const std::string path = temp_csv("vaegail_metrics_names.csv");
  CsvLog log(path, {"step", "loss"});
  expect_rejected(log, {{"step", 1}}, "the row has no value for column 'loss'");
  expect_rejected(log, {{"step", 1}, {"loss", 2}, {"lr", 3}}, "'lr' is not one of its columns");
  expect_rejected(log, {{"step", 1}, {"los", 2}}, "'los' is not one of its columns");
  EXPECT_EQ(read_file(path), "step,loss\n");
  std::remove(path.c_str());
}

// On a full file system a row is written in part, then refused: the part is cut off again, so
// that the file still ends with the last whole row, and the row goes in once there is room.
TEST(CsvLog, ARowThatDoesNotFitLeavesTheRowsBeforeWholeAndNamesTheFile) {
  SmallFileSystem small(256 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const std::string path = small.path("metrics.csv");
  std::vector<std::string> columns;
  Metrics row;
  for (int i = 0; i < 2000; ++i) {  // a row of 2000 cells: ~22 KB, several pages
    columns.push_back("c" + std::to_string(i));
    row[columns.back()] = 0.123456789;
  }
  CsvLog log(path, columns);
  log.write(row);
  const std::string before = read_file(path);
  small.fill_leaving(8192);
  const std::string error = error_of([&] { log.write(row); });
  EXPECT_TRUE(names_full_disk(error, path)) << error;
  EXPECT_EQ(read_file(path), before);
  small.make_room();
  log.write(row);
  const std::string after = read_file(path);
  EXPECT_EQ(after.substr(0, before.size()), before);
  EXPECT_EQ(after.substr(before.size()), before.substr(before.find('\n') + 1));  // the same row once more
}

TEST(SplitCsvLine, KeepsEmptyCellsIncludingATrailingOne) {
  EXPECT_EQ(split_csv_line("a,,b"), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_EQ(split_csv_line("1,2,"), (std::vector<std::string>{"1", "2", ""}));
  EXPECT_TRUE(split_csv_line("").empty());
}

TEST(CsvLog, TruncatingMetricsDropsRowsPastTheCheckpointAndATornLastRow) {
  const std::string path = temp_csv("vaegail_truncated_metrics.csv");
  write_file_atomically(path, "iteration,loss\n1,0.5\n2,0.4\n3,0.3\n4,0.");
  truncate_metrics(path, 2);
  EXPECT_EQ(read_file(path), "iteration,loss\n1,0.5\n2,0.4\n");
  write_file_atomically(path, "iteration,loss\n1,0.5\nx,0.4\n");
  try {
    truncate_metrics(path, 2);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": line 3: the first column is not a number");
  }
  std::remove(path.c_str());
  truncate_metrics(path, 2);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace vaegail
