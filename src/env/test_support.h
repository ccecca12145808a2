// Helpers shared by the env tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace vaegail {

// Writes text to a file of the temporary directory and returns its path.
inline std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace vaegail
