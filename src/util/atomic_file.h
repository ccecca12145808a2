// Files that appear whole or not at all: write to a temporary name beside the target, sync it
// to disk, then rename it over the target. A killed writer leaves at most a "*.tmp-PID" file,
// never a half target, and the next writer of the target removes it; a failing write (a full disk, an I/O error) removes the temporary file,
// leaves the target as it was and throws std::runtime_error of one line naming the target and
// the cause.
//
// Tests provoke failing writes with a file size limit (setrlimit RLIMIT_FSIZE with SIGXFSZ
// ignored, or `ulimit -f` in a shell): every write past it fails with EFBIG, as on a full disk.
#pragma once

#include <functional>
#include <string>

namespace vaegail {

// The temporary name used for `path` by this process.
std::string temporary_path_for(const std::string& path);

// temporary_path_for(path), after removing the temporary files (or folders) for `path` whose
// writer was killed before renaming them: PATH.tmp-PID where no process PID runs. A writer
// starts with it, so that a killed run's leftovers go when the run is redone.
std::string fresh_temporary_path(const std::string& path);

// Syncs the finished file `tmp` to disk, renames it to `path` and syncs the folder, so that
// `path` holds the new contents even across a power cut. When `keep_previous` is not empty, an
// existing `path` is first renamed to it (the checkpoint before). On failure `tmp` is removed.
void move_into_place(const std::string& tmp, const std::string& path, const std::string& keep_previous = {});

// Calls write(tmp_path), then move_into_place(tmp_path, path, keep_previous). Whatever write
// throws, the temporary file is removed; an exception that is not one line naming the file
// (LibTorch's c10::Error carries a stack trace) comes back as "path: FIRST LINE".
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write,
                      const std::string& keep_previous = {});

// Convenience for text and binary blobs; every write(2) is checked.
void write_file_atomically(const std::string& path, const std::string& contents,
                           const std::string& keep_previous = {});

// Reads a whole file; throws std::runtime_error naming the path if it cannot.
std::string read_file(const std::string& path);

// The first line of an exception's message: the message without LibTorch's stack trace.
std::string first_line(const std::string& message);
// Whether `message` is already one line naming `path` (then it is passed on as it is).
bool names_in_one_line(const std::string& message, const std::string& path);

}  // namespace vaegail
