// Metrics as CSV: a header of column names, then one row per call. Reopening an existing log
// with the same columns appends (a resumed run continues its curve); different columns throw.
#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace vaegail {

class CsvLog {
 public:
  CsvLog(const std::string& path, std::vector<std::string> columns);
  // One value per column, in order; flushed at once so a killed run keeps its rows.
  void write(const std::vector<double>& values);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::ofstream out_;
};

// Cells of one CSV line split on commas (no quoting: our files never quote); a trailing comma
// yields an empty last cell, so a row keeps its column count.
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace vaegail
