#include "io/regular_file.h"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>

namespace clppm {

std::string not_a_regular_file(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return std::strerror(errno);
    if (S_ISDIR(st.st_mode)) return "a folder, not a file";
    if (!S_ISREG(st.st_mode)) return "not a regular file (a FIFO, socket or device cannot be read as one)";
    return "";
}

} // namespace clppm
