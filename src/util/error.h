// The one exception type for user-facing failures: its message is a single line that names the
// file or option at fault; main() prints it and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace clppm {

struct Error : std::runtime_error {
    explicit Error(const std::string& msg) : std::runtime_error(msg) {}
};

// An error every process of an MPI job found alike (device/cluster.h): each throws it, rank 0
// alone says it, so that the job ends with one line instead of one per process.
struct ErrorOnEveryRank : Error {
    using Error::Error;
};

} // namespace clppm
