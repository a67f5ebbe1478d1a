// A double as a float, +-Inf beyond the float range. C++ leaves float(x) undefined there, and an
// optimiser may then assume the result finite and drop the isfinite check that follows (GCC did,
// for glTF positions that overflow in world space). Every narrowing of values that come from a
// file or from user-scaled arithmetic goes through this.
#pragma once
#include <limits>

namespace clppm {

inline float narrow_to_float(double x) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (x > kMax) return std::numeric_limits<float>::infinity();
    if (x < -kMax) return -std::numeric_limits<float>::infinity();
    return float(x); // NaN stays NaN
}

} // namespace clppm
