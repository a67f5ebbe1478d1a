// What an integrator reports about its render: counters, device time per phase, memory.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "device/cl.h"
#include "shared_types.h"

namespace clppm {

struct IntegratorStats {
    uint64_t passes = 0;
    uint64_t photons_emitted = 0; // total N_emitted
    uint64_t photons_stored = 0;  // total photon hits stored over all passes
    uint64_t hitpoints = 0;
    double initial_radius = 0;
    double mean_radius = 0;                      // current mean R over hit points (PPM)
    double initial_volume_radius = 0;            // SPPM and PPPM in media: the volume hit points' first radius
    double volume_radius = 0;                    // and the next pass's
    std::map<std::string, double> phase_seconds; // device time per phase, from profiling events
    size_t device_bytes = 0;                     // integrator buffers (scene buffers are counted apart)
    size_t photon_bytes = 0;                     // photon and grid buffers
    uint32_t photon_batches = 0;                 // batches the last pass's photons were traced in
    std::vector<uint32_t> device_photons;        // photons each device traced in the last pass, primary first
    std::vector<uint32_t> rank_photons;          // photons (path tracer: pixels) each MPI rank took in the last pass
    uint64_t local_work = 0;                     // photons (path tracer: pixel samples) this process traced
    uint64_t pass_launches = 0;                  // the path tracer: launches its passes took (it batches short ones)
    // --visual-importance (integrators/photon_chains.h): the chains' counts over all passes
    // (kernels/shared_types.h CHAIN_*): visible uniform paths, states deposited, mutations
    // accepted and proposed.
    uint64_t chain_counts[CHAIN_COUNTS] = {0, 0, 0, 0};
    // Kernel events of the current pass, resolved into phase_seconds at the pass's end so that
    // timing never adds a synchronisation point inside the pass.
    std::vector<std::pair<std::string, cl::Event>> pending_events;
};

// Records a kernel event of phase `phase`; collect_event_times() adds its device time to
// phase_seconds once the pass has finished.
void add_event_time(IntegratorStats& stats, const std::string& phase, const cl::Event& ev);
void collect_event_times(IntegratorStats& stats);

} // namespace clppm
