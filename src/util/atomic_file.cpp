#include "util/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vaegail {

namespace {

std::runtime_error failure(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": " + what + ": " + std::strerror(errno));
}

// fsync(2) by name. A read-only descriptor is enough on Linux, and it also syncs a folder.
void sync_path(const std::string& name, const std::string& path, const std::string& what) {
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw failure(path, what);
  const bool synced = ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  errno = error;
  if (!synced) throw failure(path, what);
}

std::string folder_of(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

void write_all(int fd, const std::string& contents, const std::string& path) {
  size_t done = 0;
  while (done < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw failure(path, "write failed");
    done += static_cast<size_t>(n);
  }
}

}  // namespace

std::string temporary_path_for(const std::string& path) {
  return path + ".tmp-" + std::to_string(static_cast<long>(getpid()));
}

std::string fresh_temporary_path(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string prefix = fs::path(path).filename().string() + ".tmp-";
  std::error_code error;
  for (fs::directory_iterator it(folder_of(path), error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string(), pid = name.substr(std::min(prefix.size(), name.size()));
    if (name.rfind(prefix, 0) != 0 || pid.empty() || pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos)
      continue;
    // kill(pid, 0) fails with ESRCH only when no process has that id; a live one's file stays.
    std::error_code ignored;  // best effort: a leftover that cannot go does not stop the write
    if (::kill(static_cast<pid_t>(std::stol(pid)), 0) != 0 && errno == ESRCH) fs::remove_all(it->path(), ignored);
  }
  return temporary_path_for(path);
}

std::string first_line(const std::string& message) { return message.substr(0, message.find('\n')); }

bool names_in_one_line(const std::string& message, const std::string& path) {
  return message.find('\n') == std::string::npos && message.find(path) != std::string::npos;
}

void move_into_place(const std::string& tmp, const std::string& path, const std::string& keep_previous) {
  try {
    sync_path(tmp, path, "cannot sync to disk");
    // Between the two renames only keep_previous exists; a reader falls back to it.
    if (!keep_previous.empty() && std::rename(path.c_str(), keep_previous.c_str()) != 0 && errno != ENOENT)
      throw failure(path, "cannot keep the file before as " + keep_previous);
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw failure(path, "cannot move finished file into place");
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  sync_path(folder_of(path), path, "cannot sync its folder to disk");
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write,
                      const std::string& keep_previous) {
  const std::string tmp = fresh_temporary_path(path);
  try {
    write(tmp);
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    if (names_in_one_line(e.what(), path)) throw;
    throw std::runtime_error(path + ": " + first_line(e.what()));
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  move_into_place(tmp, path, keep_previous);
}

void write_file_atomically(const std::string& path, const std::string& contents, const std::string& keep_previous) {
  write_atomically(
      path,
      [&](const std::string& tmp) {
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (fd < 0) throw failure(path, "cannot open for writing");
        try {
          write_all(fd, contents, path);
        } catch (...) {
          ::close(fd);
          throw;
        }
        // Some file systems (NFS) report a full disk only when the file is closed.
        if (::close(fd) != 0) throw failure(path, "write failed");
      },
      keep_previous);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace vaegail
