// Inputs are regular files: opening a FIFO (or a terminal, a socket) for reading waits for a
// writer that may never come, and a directory or a device is no image or scene. Every reader
// asks this first, so such a path is refused at once, under mpirun too, instead of hanging.
#pragma once
#include <string>

namespace clppm {

// Why `path` cannot be read as a file ("No such file or directory", "not a regular file (a FIFO,
// a device or a folder)", ...), or "" when it is a regular file. Never opens the path.
std::string not_a_regular_file(const std::string& path);

} // namespace clppm
