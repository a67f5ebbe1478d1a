// Output files appear whole or not at all: every write goes to a temporary file in the target's
// directory, is fsync'ed, then rename()d into place, so an interrupted or failed write never
// leaves a truncated image and never clobbers the previous one.
#pragma once
#include <string>

namespace clppm {

// Writes `contents` to `path` atomically (temp file ".<name>.tmp.<pid>" beside it, fsync,
// rename). On failure the temp file is removed, the old file is untouched, and clppm::Error is
// thrown with one line: "cannot write PATH: REASON".
void write_file_atomic(const std::string& path, const std::string& contents);

// Checks up front (before a long render) that `path` could be written: its directory exists, is
// a directory and accepts a new file, and `path` itself is not a directory. Throws clppm::Error in
// the same style as write_file_atomic. Probes by creating and removing a temp file, because
// access(2) says yes to root even on directories it cannot write (read-only mounts, ACLs).
void check_writable(const std::string& path);

// The directory part of `path` ("." when it has none); "/" stays "/".
std::string parent_directory(const std::string& path);

} // namespace clppm
