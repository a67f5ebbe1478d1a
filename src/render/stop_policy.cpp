#include "render/stop_policy.h"

namespace clppm {

StopReason StopPolicy::check(uint64_t passes, double seconds, bool target_reached, bool interrupt,
                             bool viewer_stop) const {
    if (pass_limit > 0 && passes >= pass_limit) return StopReason::Passes;
    // A time limit shorter than the first pass still renders that pass: never an empty image.
    if (time_limit > 0 && seconds >= time_limit && passes > 0) return StopReason::Time;
    if (target_reached) return StopReason::TargetError;
    if (viewer_stop) return StopReason::Viewer;
    if (interrupt) return StopReason::Interrupt;
    return StopReason::None;
}

} // namespace clppm
