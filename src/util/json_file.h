// JSON files the runs write (specs, options, state): a parse error names the file.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "util/atomic_file.h"

namespace vaegail {

inline nlohmann::json read_json_file(const std::string& path) {
  try {
    return nlohmann::json::parse(read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": malformed JSON: " + e.what());
  }
}

}  // namespace vaegail
