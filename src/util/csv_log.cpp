#include "util/csv_log.h"

#include <cstdio>
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

void CsvLog::write(const std::vector<double>& values) {
  if (values.size() != columns_.size())
    throw std::logic_error(path_ + ": row has " + std::to_string(values.size()) +
                           " values for " + std::to_string(columns_.size()) + " columns");
  char buf[32];
  for (size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.8g", values[i]);
    out_ << (i ? "," : "") << buf;
  }
  out_ << "\n" << std::flush;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace vaegail
