#include "integrators/integrator_stats.h"

namespace clppm {

void add_event_time(IntegratorStats& stats, const std::string& phase, const cl::Event& ev) {
    stats.pending_events.emplace_back(phase, ev);
}

void collect_event_times(IntegratorStats& stats) {
    for (auto& [phase, ev] : stats.pending_events) {
        try {
            ev.wait();
            cl_ulong t0 = ev.getProfilingInfo<CL_PROFILING_COMMAND_START>();
            cl_ulong t1 = ev.getProfilingInfo<CL_PROFILING_COMMAND_END>();
            stats.phase_seconds[phase] += double(t1 - t0) * 1e-9;
        } catch (const cl::Error&) {
            // Profiling unavailable for this event: the phase time stays as it was.
        }
    }
    stats.pending_events.clear();
}

} // namespace clppm
