#include "util/csv_log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
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
  existing.close();
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(path + ": cannot open metrics log for writing: " + std::strerror(errno));
  try {
    if (!has_header) append(header + "\n");
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

CsvLog::~CsvLog() { ::close(fd_); }

void CsvLog::append(const std::string& line) {
  struct stat before;
  if (::fstat(fd_, &before) != 0)
    throw std::runtime_error(path_ + ": cannot append to metrics log: " + std::strerror(errno));
  for (size_t done = 0; done < line.size();) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int cause = errno;
      // Should the cut fail too, the torn row has no newline, and a resumed run drops it
      // (gail/run_dir.h's truncate_metrics).
      const bool cut = ::ftruncate(fd_, before.st_size) == 0;
      throw std::runtime_error(path_ + ": cannot append to metrics log: " + std::strerror(cause) +
                               (cut ? "" : " (a torn last row is left)"));
    }
    done += static_cast<size_t>(n);
  }
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
  append(line + "\n");
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
