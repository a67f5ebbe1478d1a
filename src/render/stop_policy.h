// When a render stops (one policy, asked before every pass): the pass limit, the time limit, the
// target error, a stop request (Ctrl-C, SIGTERM, KeyboardInterrupt: util/cancellation.h) and an
// observer's Stop.
#pragma once
#include <cstdint>

namespace clppm {

enum class StopReason { None, Passes, Time, TargetError, Interrupt, Viewer };

struct StopPolicy {
    uint64_t pass_limit = 0; // 0: none
    double time_limit = 0;   // seconds of rendering, after at least one pass; 0: none

    // Why the render must stop now, or None to go on. `passes` counts from the start of the
    // original render (a resumed one included), `seconds` this run only.
    StopReason check(uint64_t passes, double seconds, bool target_reached, bool interrupt, bool viewer_stop) const;
};

} // namespace clppm
