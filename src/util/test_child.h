// Test support: runs code in a forked child, for what may crash or hang (a segfault inside a
// C library cannot be caught in-process) or must not touch the test process (a file size
// limit). Header-only: tests of several stages include it.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <string>

namespace vaegail {

struct ChildOutcome {
  enum class End { kExited, kCrashed, kTimedOut } end = End::kCrashed;
  int code = 0;        // the exit status, or the signal that ended the child
  std::string report;  // what the body returned in `report`
};

// Forks; the child runs body(report) under an alarm of `timeout_s` seconds and exits with its
// return value, sending `report` back through a pipe. The parent waits for it.
inline ChildOutcome run_in_child(const std::function<int(std::string& report)>& body, unsigned timeout_s) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    close(pipe_fds[0]);
    alarm(timeout_s);
    std::string report;
    const int code = body(report);
    for (size_t done = 0; done < report.size();) {
      const ssize_t n = write(pipe_fds[1], report.data() + done, report.size() - done);
      if (n <= 0) break;
      done += static_cast<size_t>(n);
    }
    _exit(code);  // no atexit handlers or static destructors of the parent's state
  }
  close(pipe_fds[1]);
  ChildOutcome outcome;
  char buffer[4096];
  for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;) outcome.report.append(buffer, n);
  close(pipe_fds[0]);
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) != pid) return outcome;
  if (WIFEXITED(status)) {
    outcome.end = ChildOutcome::End::kExited;
    outcome.code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    outcome.end = WTERMSIG(status) == SIGALRM ? ChildOutcome::End::kTimedOut : ChildOutcome::End::kCrashed;
    outcome.code = WTERMSIG(status);
  }
  return outcome;
}

// For a child: every write that would make a file longer than `bytes` fails with EFBIG, as on
// a full disk (SIGXFSZ, which would kill the process instead, is ignored).
inline void limit_file_size(rlim_t bytes) {
  const rlimit limit{bytes, bytes};
  setrlimit(RLIMIT_FSIZE, &limit);
  signal(SIGXFSZ, SIG_IGN);
}

// Whether any process left a temporary file for `path` (util/atomic_file.h's "PATH.tmp-PID"):
// a forked writer's temporary name carries the child's pid, not the test's.
inline bool leaves_temporary(const std::string& path) {
  const std::filesystem::path target(path);
  const std::string prefix = target.filename().string() + ".tmp-";
  for (const auto& entry : std::filesystem::directory_iterator(target.parent_path()))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace vaegail
