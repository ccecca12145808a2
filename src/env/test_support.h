// Helpers shared by the env tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace vaegail {

// Writes text to a file of the temporary directory and returns its path. The name carries the
// process id: ctest -j runs tests as separate processes at once, and two writing one fixed path
// read each other's half-written file.
inline std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace vaegail
