#include "util/atomic_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

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

TEST(AtomicFile, ReadingAMissingFileNamesIt) {
  try {
    read_file("/nonexistent/vaegail.txt");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/vaegail.txt"), std::string::npos);
  }
}

}  // namespace
}  // namespace vaegail
