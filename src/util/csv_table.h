// A CSV file with a header row, read whole for `vaegail plot`: metrics logs (util/csv_log.h), VAE
// embeddings (eval/embedding.h) or any table a user brings. Cells stay text until a column is
// asked for as numbers, so string columns (expert ids) do not get in the way.
//
// The format is the plain one the project writes: comma-separated, no quoting, one row per
// line; blank lines are skipped. Errors are one line naming the file, line and column.
#pragma once

#include <string>
#include <vector>

namespace vaegail {

class CsvTable {
 public:
  // `where` names the source in errors (usually the path).
  static CsvTable parse(const std::string& text, const std::string& where);
  static CsvTable read(const std::string& path);

  const std::vector<std::string>& columns() const { return columns_; }
  int rows() const { return static_cast<int>(cells_.size()); }
  bool has_column(const std::string& name) const;

  // A column's cells as finite numbers; throws std::invalid_argument when the column is
  // missing (listing the ones there are) or a cell is not a finite number.
  std::vector<double> numbers(const std::string& column) const;
  std::vector<std::string> strings(const std::string& column) const;

 private:
  int index_of(const std::string& column) const;

  std::string where_;
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> cells_;  // [rows][columns]
  std::vector<int> line_numbers_;                // of each row in the file, for errors
};

}  // namespace vaegail
