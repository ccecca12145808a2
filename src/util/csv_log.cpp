#include "util/csv_log.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.h"

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

namespace {
int metrics_row_number(const std::string& line, int line_number, const std::string& path) {
  try {
    return std::stoi(line.substr(0, line.find(',')));
  } catch (const std::exception&) {
    throw std::runtime_error(path + ": line " + std::to_string(line_number) + ": the first column is not a number");
  }
}
}  // namespace

void truncate_metrics(const std::string& path, int last) {
  if (!std::filesystem::exists(path)) return;
  std::istringstream in(read_file(path));
  std::string line, kept;
  for (int number = 1; std::getline(in, line); ++number) {
    if (in.eof()) break;  // a line without its newline: torn by a kill mid-write
    if (number == 1 || (!line.empty() && metrics_row_number(line, number, path) <= last)) kept += line + "\n";
  }
  write_file_atomically(path, kept);
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace vaegail
