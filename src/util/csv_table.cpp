#include "util/csv_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/csv_log.h"

namespace vaegail {
namespace {

std::string without_carriage_return(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

}  // namespace

CsvTable CsvTable::parse(const std::string& text, const std::string& where) {
  CsvTable table;
  table.where_ = where;
  std::stringstream in(text);
  std::string line;
  int number = 0;
  while (table.columns_.empty() && std::getline(in, line)) {
    ++number;
    line = without_carriage_return(line);
    if (!line.empty()) table.columns_ = split_csv_line(line);
  }
  if (table.columns_.empty()) throw std::invalid_argument(where + ": no header row (empty file)");
  while (std::getline(in, line)) {
    ++number;
    line = without_carriage_return(line);
    if (line.empty()) continue;
    auto cells = split_csv_line(line);
    if (cells.size() != table.columns_.size())
      throw std::invalid_argument(where + ": line " + std::to_string(number) + ": " +
                                  std::to_string(cells.size()) + " cells, header has " +
                                  std::to_string(table.columns_.size()));
    table.cells_.push_back(std::move(cells));
    table.line_numbers_.push_back(number);
  }
  return table;
}

CsvTable CsvTable::read(const std::string& path) { return parse(read_file(path), path); }

bool CsvTable::has_column(const std::string& name) const {
  for (const auto& c : columns_)
    if (c == name) return true;
  return false;
}

int CsvTable::index_of(const std::string& column) const {
  for (size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i] == column) return static_cast<int>(i);
  // Wide tables (embeddings have 2d latent columns) are listed by their first columns.
  constexpr size_t kListed = 12;
  std::string have;
  for (size_t i = 0; i < std::min(columns_.size(), kListed); ++i) have += (i ? ", " : "") + columns_[i];
  if (columns_.size() > kListed) have += ", ... " + std::to_string(columns_.size()) + " in all";
  throw std::invalid_argument(where_ + ": no column '" + column + "' (columns: " + have + ")");
}

std::vector<double> CsvTable::numbers(const std::string& column) const {
  const int c = index_of(column);
  std::vector<double> values;
  values.reserve(cells_.size());
  for (size_t r = 0; r < cells_.size(); ++r) {
    const std::string& cell = cells_[r][static_cast<size_t>(c)];
    double v = NAN;
    size_t used = 0;
    try {
      v = std::stod(cell, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != cell.size() || !std::isfinite(v))
      throw std::invalid_argument(where_ + ": line " + std::to_string(line_numbers_[r]) +
                                  ": column '" + column + "': '" + cell +
                                  "' is not a finite number");
    values.push_back(v);
  }
  return values;
}

std::vector<std::string> CsvTable::strings(const std::string& column) const {
  const int c = index_of(column);
  std::vector<std::string> values;
  values.reserve(cells_.size());
  for (const auto& row : cells_) values.push_back(row[static_cast<size_t>(c)]);
  return values;
}

}  // namespace vaegail
