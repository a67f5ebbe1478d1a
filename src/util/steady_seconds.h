// Seconds on the steady clock (an arbitrary epoch): for measuring how long something took.
#pragma once
#include <chrono>

namespace clppm {

inline double steady_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace clppm
