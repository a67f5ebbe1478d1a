#include "render/stop_policy.h"

namespace clppm {

StopReason StopPolicy::check(uint64_t passes, double seconds, bool target_reached, bool interrupt,
                             bool viewer_stop) const {
    if (pass_limit > 0 && passes >= pass_limit) return StopReason::Passes;
    if (time_limit > 0 && seconds >= time_limit) return StopReason::Time;
    if (target_reached) return StopReason::TargetError;
    if (viewer_stop) return StopReason::Viewer;
    if (interrupt) return StopReason::Interrupt;
    return StopReason::None;
}

} // namespace clppm
