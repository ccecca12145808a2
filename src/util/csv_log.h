// Metrics as CSV: a header of column names, then one row per call. Reopening an existing log
// with the same columns appends (a resumed run continues its curve); different columns throw.
// Every row goes to the file at once with write(2), each call checked: a row that does not fit (a
// full disk, an I/O error) is cut off again, so that the rows before it stay whole, and the error
// is one line naming the file and the cause.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace vaegail {

// One row's values by column name.
using Metrics = std::map<std::string, double>;

class CsvLog {
 public:
  CsvLog(const std::string& path, std::vector<std::string> columns);
  ~CsvLog();
  CsvLog(const CsvLog&) = delete;
  CsvLog& operator=(const CsvLog&) = delete;
  // A value for every column, written in the columns' order; a missing or unknown name throws
  // std::logic_error naming it. In the file when this returns, so a killed run keeps its rows.
  void write(const Metrics& row);
  const std::string& path() const { return path_; }

 private:
  void append(const std::string& line);
  std::string path_;
  std::vector<std::string> columns_;
  int fd_ = -1;
};

// Drops the rows of a metrics CSV whose first column (the iteration or epoch) exceeds `last`:
// rows a run logged after its last checkpoint before it was killed, which the resumed run redoes;
// and a last line without its newline (torn by the kill). A first column that is not a number
// throws one line naming the file and the line. A missing file is left missing.
void truncate_metrics(const std::string& path, int last);

// Cells of one CSV line split on commas (no quoting: our files never quote); a trailing comma
// yields an empty last cell, so a row keeps its column count.
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace vaegail
