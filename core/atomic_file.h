// Outputs are written to a temporary name beside the target and renamed into place, so that a
// killed run leaves the old file or none, never half a file.
#pragma once

#include <string>
#include <string_view>

namespace shatter {

// Writes `bytes` to `path` atomically: PATH.tmp.PID, fsync, rename. Throws Error(Io) naming the
// path on failure and removes the temporary file.
void write_file_atomic(const std::string& path, std::string_view bytes);

// Reads a whole file; throws Error(BadInput) naming the file when it is missing or unreadable.
std::string read_file(const std::string& path, const char* what = "file");

// Creates a directory and its parents; throws Error(Io) naming it on failure.
void make_directories(const std::string& path);

}  // namespace shatter
