#include "util/run_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "util/world.h"

namespace vaegail {

namespace fs = std::filesystem;

namespace {

std::runtime_error lock_failure(const std::string& lock_file, const std::string& what, int error) {
  return std::runtime_error(lock_file + ": " + what + ": " + std::strerror(error));
}

// Whether the open file `fd` is still the one named `path`. A holder removes its lock file just
// before releasing it, so a process that opened the file before the removal can take a lock on a
// name no one else will open again: it must try again on the file now at `path`.
bool still_named(int fd, const std::string& path) {
  struct stat open_file, named;
  return ::fstat(fd, &open_file) == 0 && ::stat(path.c_str(), &named) == 0 && open_file.st_dev == named.st_dev &&
         open_file.st_ino == named.st_ino;
}

// "process PID" from the lock file the holder wrote; the holder writes its pid just after taking
// the lock, so an empty file is given a moment. A holder on a full disk may never write it.
std::string holder_of(int fd) {
  for (int attempt = 0; attempt < 20; ++attempt) {
    char text[32];
    const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
    if (n > 0) {
      const std::string pid(text, static_cast<size_t>(n));
      return "process " + pid.substr(0, pid.find('\n'));
    }
    ::usleep(10'000);
  }
  return "another process";
}

// The pid is for a refused process's message only: the lock holds without it (on a full disk,
// writing it fails while the lock itself is taken), so a failed write is not an error.
void record_pid(int fd) {
  const std::string pid = std::to_string(static_cast<long>(::getpid())) + "\n";
  if (::ftruncate(fd, 0) != 0) return;
  if (::pwrite(fd, pid.data(), pid.size(), 0) < 0) return;
}

}  // namespace

RunLock::RunLock(const std::string& lock_file, const std::string& subject) : path_(lock_file) {
  std::error_code error;
  const fs::path folder = fs::path(lock_file).parent_path();
  if (!folder.empty()) fs::create_directories(folder, error);
  if (error) throw std::runtime_error(folder.string() + ": cannot create: " + error.message());
  while (fd_ < 0) {
    const int fd = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw lock_failure(lock_file, "cannot open the run's lock", errno);
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int cause = errno;
      if (cause == EWOULDBLOCK) {
        const std::string holder = holder_of(fd);
        ::close(fd);
        throw std::runtime_error(subject + ": in use by " + holder + " (another vaegail run)");
      }
      ::close(fd);
      throw lock_failure(lock_file, "cannot lock", cause);
    }
    if (still_named(fd, lock_file))
      fd_ = fd;
    else
      ::close(fd);
  }
  record_pid(fd_);
}

RunLock::RunLock(RunLock&& other) noexcept : fd_(other.fd_), path_(std::move(other.path_)) { other.fd_ = -1; }

RunLock& RunLock::operator=(RunLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = other.fd_;
    path_ = std::move(other.path_);
    other.fd_ = -1;
  }
  return *this;
}

RunLock::~RunLock() { release(); }

void RunLock::release() {
  if (fd_ < 0) return;
  // Removed while still held, so that the name never points at a released lock file that a
  // process could lock after another has taken the new one (see still_named).
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

RunLock lock_run_directory(const std::string& dir) {
  if (!World::get().is_root()) return {};
  return RunLock((fs::path(dir) / ".lock").string(), dir);
}

RunLock lock_output_file(const std::string& path) {
  if (!World::get().is_root()) return {};
  const fs::path file(path);
  return RunLock((file.parent_path() / ("." + file.filename().string() + ".lock")).string(), path);
}

}  // namespace vaegail
