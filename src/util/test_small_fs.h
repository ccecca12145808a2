// Test support: a real, small file system for the tests of every writer on a full disk. A file
// size limit (test_child.h) makes write(2) fail with EFBIG at one chosen length; a full tmpfs
// fails where a full disk does: ENOSPC from whichever write (HDF5's, LibTorch's, FFmpeg's own
// buffered ones included) finds no free page. Mounting needs root, which CI has; elsewhere a test
// skips with the reason. Header-only: tests of several stages include it.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "util/atomic_file.h"
#include "util/test_error.h"

namespace vaegail {

class SmallFileSystem {
 public:
  // A tmpfs of `bytes` (rounded up to pages) on a new folder under the temporary directory.
  explicit SmallFileSystem(std::size_t bytes) {
    std::string folder = (std::filesystem::temp_directory_path() / "vaegail_small_fs_XXXXXX").string();
    if (::geteuid() != 0) {
      why_not_ = "mounting a small tmpfs needs root (CI runs the tests as root)";
      return;
    }
    if (::mkdtemp(folder.data()) == nullptr) {
      why_not_ = folder + ": " + std::strerror(errno);
      return;
    }
    root_ = folder;
    const std::string size = "size=" + std::to_string(bytes);
    if (::mount("tmpfs", root_.c_str(), "tmpfs", MS_NOSUID | MS_NODEV, size.c_str()) != 0)
      why_not_ = "mount -t tmpfs on " + root_ + ": " + std::strerror(errno);
  }
  ~SmallFileSystem() {
    if (root_.empty()) return;
    if (mounted()) ::umount2(root_.c_str(), MNT_DETACH);
    ::rmdir(root_.c_str());
  }
  SmallFileSystem(const SmallFileSystem&) = delete;
  SmallFileSystem& operator=(const SmallFileSystem&) = delete;

  bool mounted() const { return why_not_.empty(); }
  const std::string& why_not() const { return why_not_; }  // for GTEST_SKIP()
  // A path on it.
  std::string path(const std::string& name) const { return root_ + "/" + name; }

  // Takes all of the free space but `bytes` with a ballast file, so that the next writes fail
  // once they need more.
  void fill_leaving(std::size_t bytes) {
    struct statvfs s;
    if (::statvfs(root_.c_str(), &s) != 0) return;
    const std::size_t free = static_cast<std::size_t>(s.f_bavail) * s.f_frsize;
    const int fd = ::open(ballast().c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    const std::vector<char> zeros(1 << 16, 0);
    for (std::size_t left = free > bytes ? free - bytes : 0; left > 0;) {
      const ssize_t n = ::write(fd, zeros.data(), std::min(left, zeros.size()));
      if (n <= 0) break;
      left -= static_cast<std::size_t>(n);
    }
    ::close(fd);
  }
  // Gives the ballast's space back: the disk has room again.
  void make_room() const { std::filesystem::remove(ballast()); }

 private:
  std::string ballast() const { return root_ + "/ballast"; }
  std::string root_, why_not_;
};

// Whether `message` is what a write on a full disk must say: one line naming `path` and the cause.
inline bool names_full_disk(const std::string& message, const std::string& path) {
  return message.find('\n') == std::string::npos && message.find(path) != std::string::npos &&
         message.find(std::strerror(ENOSPC)) != std::string::npos;
}

// The files under `dir` (recursively) whose names hold "tmp": what a failed write must not leave.
inline std::vector<std::string> temporary_files_under(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.path().filename().string().find("tmp") != std::string::npos) found.push_back(entry.path().string());
  return found;
}

// `save` writes `path`, on `small`. Once there is no room, it must fail in one line naming path and
// the cause, leave no temporary file and leave path as the save before wrote it (still loadable);
// once there is room again, it saves.
inline void expect_refused_on_a_full_disk_then_saved(SmallFileSystem& small, const std::string& path,
                                                     const std::function<void()>& save) {
  save();
  const std::string before = read_file(path);
  small.fill_leaving(0);
  const std::string error = error_of(save);
  EXPECT_TRUE(names_full_disk(error, path)) << "'" << error << "' from writing " << path;
  EXPECT_EQ(temporary_files_under(small.path("")), std::vector<std::string>{});
  EXPECT_TRUE(read_file(path) == before) << path << " changed";
  small.make_room();
  save();
}

}  // namespace vaegail
