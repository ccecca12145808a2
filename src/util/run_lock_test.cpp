#include "util/run_lock.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "util/test_error.h"

namespace vaegail {
namespace {

namespace fs = std::filesystem;

class RunLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = (fs::temp_directory_path() / ("vaegail_run_lock_" + std::to_string(::getpid()))).string();
    fs::remove_all(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  std::string refusal(pid_t holder) const {
    return dir + ": in use by process " + std::to_string(holder) + " (another vaegail run)";
  }

  std::string dir;
};

// A child process that takes the run directory's lock, says so through a pipe and then waits to
// be killed.
pid_t child_holding(const std::string& dir) {
  int ready[2];
  if (::pipe(ready) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(ready[0]);
    const RunLock lock = lock_run_directory(dir);
    if (::write(ready[1], "y", 1) != 1) ::_exit(1);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char answer = 0;
  if (pid < 0 || ::read(ready[0], &answer, 1) != 1) answer = 0;
  ::close(ready[0]);
  return answer == 'y' ? pid : -1;
}

TEST_F(RunLockTest, ASecondProcessIsRefusedInOneLineNamingTheHolderUntilTheHolderIsKilled) {
  const pid_t holder = child_holding(dir);
  ASSERT_GT(holder, 0);
  EXPECT_EQ(one_line_error_of([&] { lock_run_directory(dir); }), refusal(holder));
  EXPECT_EQ(one_line_error_of([&] { lock_run_directory(dir); }), refusal(holder));  // refusing changes nothing

  // The kernel releases a killed process's lock: nothing stale to clear.
  ::kill(holder, SIGKILL);
  ::waitpid(holder, nullptr, 0);
  EXPECT_TRUE(fs::exists(dir + "/.lock"));  // left by the kill, yet free
  const RunLock lock = lock_run_directory(dir);
  EXPECT_TRUE(lock.held());
}

TEST_F(RunLockTest, TheHolderWritesItsPidAndRemovesTheFileOnRelease) {
  {
    const RunLock lock = lock_run_directory(dir);
    std::string pid;
    std::getline(std::ifstream(dir + "/.lock") >> std::ws, pid);
    EXPECT_EQ(pid, std::to_string(::getpid()));
  }
  EXPECT_FALSE(fs::exists(dir + "/.lock"));
  const RunLock again = lock_run_directory(dir);  // released: the next run takes it
  EXPECT_TRUE(again.held());
}

TEST_F(RunLockTest, OneProcessTakingItTwiceIsRefusedToo) {
  const RunLock lock = lock_run_directory(dir);
  EXPECT_EQ(one_line_error_of([&] { lock_run_directory(dir); }), refusal(::getpid()));
}

TEST_F(RunLockTest, AMovedLockIsStillHeldAndReleasedOnce) {
  RunLock first = lock_run_directory(dir);
  RunLock second = std::move(first);
  EXPECT_FALSE(first.held());
  EXPECT_TRUE(second.held());
  second = RunLock();
  EXPECT_FALSE(fs::exists(dir + "/.lock"));
}

TEST_F(RunLockTest, AnOutputFilesLockLiesBesideItAndNamesIt) {
  const std::string file = dir + "/demos.h5";
  const RunLock lock = lock_output_file(file);
  EXPECT_TRUE(fs::exists(dir + "/.demos.h5.lock"));
  EXPECT_EQ(one_line_error_of([&] { lock_output_file(file); }),
            file + ": in use by process " + std::to_string(::getpid()) + " (another vaegail run)");
  const RunLock other = lock_output_file(dir + "/other.h5");  // another output in the same folder
  EXPECT_TRUE(other.held());
}

}  // namespace
}  // namespace vaegail
