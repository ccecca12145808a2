// One run directory, one writer. A training process holds an exclusive flock(2) on a lock file of
// its run directory (or beside its output file) for its whole life, with its pid in it. The kernel
// releases the lock when the process ends, however it ends (SIGKILL included), so a lock is never
// stale and never needs clearing by hand. A second process on the same run is refused at once, in
// one line naming the holder: two writers would interleave their metrics rows and checkpoints
// without a word, and waiting for the first would only hide that the command was started twice.
#pragma once

#include <string>

namespace vaegail {

class RunLock {
 public:
  RunLock() = default;  // holds nothing (a rank other than 0 under mpirun)
  // Takes `lock_file` (creating its folder) and writes this process's pid into it. When another
  // process holds it, throws std::runtime_error "SUBJECT: in use by process PID (another vaegail
  // run)", `subject` being what the user named (the run directory or the output file).
  RunLock(const std::string& lock_file, const std::string& subject);
  RunLock(RunLock&& other) noexcept;
  RunLock& operator=(RunLock&& other) noexcept;
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;
  ~RunLock();  // removes the lock file, then releases the lock

  bool held() const { return fd_ >= 0; }

 private:
  void release();
  int fd_ = -1;
  std::string path_;
};

// The lock of the run directory `dir`: DIR/.lock. Under mpirun only rank 0 takes it, since the
// ranks of one run are one writer (util/world.h); the other ranks get a RunLock holding nothing.
RunLock lock_run_directory(const std::string& dir);

// The lock of a job whose output is the one file `path`: .NAME.lock beside it, rank 0 only.
RunLock lock_output_file(const std::string& path);

}  // namespace vaegail
