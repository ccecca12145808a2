#include "util/atomic_file.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "util/test_child.h"

namespace vaegail {
namespace {

std::string scratch(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("vaegail_atomic_" + name)).string();
}

TEST(AtomicFile, WritesWholeFile) {
  const std::string path = scratch("whole.txt");
  write_file_atomically(path, "hello");
  EXPECT_EQ(read_file(path), "hello");
  EXPECT_FALSE(std::filesystem::exists(temporary_path_for(path)));
  std::remove(path.c_str());
}

TEST(AtomicFile, FailedWriteLeavesTargetAndNoTemporary) {
  const std::string path = scratch("keep.txt");
  write_file_atomically(path, "old");
  EXPECT_THROW(write_atomically(path,
                                [](const std::string& tmp) {
                                  FILE* f = std::fopen(tmp.c_str(), "w");
                                  std::fputs("half", f);
                                  std::fclose(f);
                                  throw std::runtime_error("killed");
                                }),
               std::runtime_error);
  EXPECT_EQ(read_file(path), "old");
  EXPECT_FALSE(std::filesystem::exists(temporary_path_for(path)));
  std::remove(path.c_str());
}

// The id of a process that has ended and been reaped: no process has it now.
pid_t ended_process() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  waitpid(pid, nullptr, 0);
  return pid;
}

// A writer SIGKILLed mid-write leaves PATH.tmp-PID (a file, or data_export's folder); the next write
// of PATH removes it, but not the file of a writer still running, nor a name that only looks like one.
TEST(AtomicFile, TheNextWriteRemovesTheTemporaryFilesOfKilledWriters) {
  const std::string path = scratch("killed.txt");
  const std::string left_file = path + ".tmp-" + std::to_string(ended_process()),
                    left_folder = path + ".tmp-" + std::to_string(ended_process()),
                    running = path + ".tmp-" + std::to_string(getppid()), other = path + ".tmp-notes";
  for (const auto& name : {left_file, running, other}) std::fclose(std::fopen(name.c_str(), "w"));
  std::filesystem::create_directories(left_folder + "/data");
  write_file_atomically(path, "new");
  EXPECT_EQ(read_file(path), "new");
  EXPECT_FALSE(std::filesystem::exists(left_file));
  EXPECT_FALSE(std::filesystem::exists(left_folder));
  EXPECT_TRUE(std::filesystem::exists(running));
  EXPECT_TRUE(std::filesystem::exists(other));
  for (const auto& name : {path, running, other}) std::remove(name.c_str());
}

TEST(AtomicFile, ReadingAMissingFileNamesIt) {
  try {
    read_file("/nonexistent/vaegail.txt");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/vaegail.txt"), std::string::npos);
  }
}

TEST(AtomicFile, KeepPreviousKeepsTheFileItReplaces) {
  const std::string path = scratch("rotated.txt"), previous = scratch("rotated.previous.txt");
  std::remove(previous.c_str());
  write_file_atomically(path, "one", previous);
  EXPECT_FALSE(std::filesystem::exists(previous));  // nothing to keep the first time
  write_file_atomically(path, "two", previous);
  EXPECT_EQ(read_file(path), "two");
  EXPECT_EQ(read_file(previous), "one");
  std::remove(path.c_str());
  std::remove(previous.c_str());
}

TEST(AtomicFile, AMultiLineErrorComesBackAsOneLineNamingTheFile) {
  const std::string path = scratch("trace.bin");
  try {
    write_atomically(path, [](const std::string&) {
      throw std::runtime_error("PytorchStreamWriter failed writing file data/0\nframe #0: c10::Error");
    });
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": PytorchStreamWriter failed writing file data/0");
  }
}

void expect_one_line_naming(const std::string& message, const std::string& path, const std::string& cause) {
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(cause), std::string::npos) << message << " lacks " << cause;
}

TEST(AtomicFile, AFullDiskEndsInOneLineNamingTheFileAndKeepsTheOldOne) {
  const std::string path = scratch("full.txt");
  write_file_atomically(path, "old");
  // The temporary name leads to /dev/full, where every write fails with ENOSPC.
  std::filesystem::create_symlink("/dev/full", temporary_path_for(path));
  try {
    write_file_atomically(path, "new");
    FAIL();
  } catch (const std::runtime_error& e) {
    expect_one_line_naming(e.what(), path, std::strerror(ENOSPC));
  }
  EXPECT_EQ(read_file(path), "old");
  EXPECT_FALSE(leaves_temporary(path));
  std::remove(path.c_str());
}

TEST(AtomicFile, AWritePastTheFileSizeLimitKeepsBothOldFiles) {
  const std::string path = scratch("limit.txt"), previous = scratch("limit.previous.txt");
  write_file_atomically(path, "first");
  write_file_atomically(path, "second", previous);
  const ChildOutcome outcome = run_in_child(
      [&](std::string& report) {
        limit_file_size(1024);
        try {
          write_file_atomically(path, std::string(4096, 'x'), previous);
        } catch (const std::exception& e) {
          report = e.what();
          return 0;
        }
        return 1;
      },
      10);
  ASSERT_EQ(outcome.end, ChildOutcome::End::kExited);
  ASSERT_EQ(outcome.code, 0) << "the write did not fail";
  expect_one_line_naming(outcome.report, path, std::strerror(EFBIG));
  EXPECT_EQ(read_file(path), "second");
  EXPECT_EQ(read_file(previous), "first");
  EXPECT_FALSE(leaves_temporary(path));
  std::remove(path.c_str());
  std::remove(previous.c_str());
}

}  // namespace
}  // namespace vaegail
