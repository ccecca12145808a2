// Files that appear whole or not at all: write to a temporary name beside the target, then
// rename over it. A killed writer leaves at most a "*.tmp-PID" file, never a half target.
#pragma once

#include <functional>
#include <string>

namespace vaegail {

// The temporary name used for `path` by this process.
std::string temporary_path_for(const std::string& path);

// Calls write(tmp_path), then renames tmp_path to path. If write throws, the temporary file
// is removed and the exception propagates; path is untouched.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Convenience for text and binary blobs.
void write_file_atomically(const std::string& path, const std::string& contents);

// Reads a whole file; throws std::runtime_error naming the path if it cannot.
std::string read_file(const std::string& path);

}  // namespace vaegail
