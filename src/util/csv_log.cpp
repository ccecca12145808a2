#include "util/csv_log.h"

#include <algorithm>
#include <fmt/format.h>
#include <sstream>
#include <stdexcept>

namespace vaegail {

namespace {
std::string join(const std::vector<std::string>& columns) {
  std::string line;
  for (size_t i = 0; i < columns.size(); ++i) line += (i ? "," : "") + columns[i];
  return line;
}
}  // namespace

CsvLog::CsvLog(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  const std::string header = join(columns_);
  std::ifstream existing(path);
  std::string first;
  const bool has_header = existing && std::getline(existing, first) && !first.empty();
  if (has_header && first != header)
    throw std::runtime_error(path + ": existing metrics have columns '" + first +
                             "', expected '" + header + "'");
  out_.open(path, std::ios::app);
  if (!out_) throw std::runtime_error(path + ": cannot open metrics log for writing");
  if (!has_header) out_ << header << "\n" << std::flush;
}

void CsvLog::write(const Metrics& row) {
  for (const auto& [name, value] : row)
    if (std::find(columns_.begin(), columns_.end(), name) == columns_.end())
      throw std::logic_error(path_ + ": '" + name + "' is not one of its columns");
  std::string line;
  for (const auto& column : columns_) {
    const auto value = row.find(column);
    if (value == row.end()) throw std::logic_error(path_ + ": the row has no value for column '" + column + "'");
    line += (line.empty() ? "" : ",") + fmt::format("{:.8g}", value->second);
  }
  out_ << line << "\n" << std::flush;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace vaegail
