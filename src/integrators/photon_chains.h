// Visual importance for photon tracing (Hachisuka and Jensen 2009, kernels/photon_chain.cl): one
// Markov chain of photon paths per photon index of a pass, whose target is the path's visibility
// to this pass's hit points. PhotonMap drives it: mark() before a pass's photons, the chain kernel
// in place of photon_trace, commit_batch() once a batch's photons fit, end_pass() after the last.
// The film divides by effective_emitted() in place of the photons emitted.
#pragma once
#include <cstdint>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/integrator_stats.h"
#include "io/checkpoint.h"
#include "shared_types.h"

namespace clppm {

class PhotonChains {
public:
    // `chains` chains (PHOTON_CHAIN_STEPS uniform paths each per pass).
    PhotonChains(const DeviceContext& dc, const cl::Program& program, IntegratorStats& stats, uint64_t chains);

    // Marks the cells that the spheres of the n hit points overlap (radius R(x) from hit_stats, or
    // global_r2 when > 0): where photons may be gathered this pass. The marks of earlier passes
    // stay, so that V only grows and soon stops changing: a state visible once stays visible, and
    // the chains keep one target (SPPM's hit points differ every pass; a target that changed with
    // them would leave states no pass sees, and a darker image). The first call fixes the cells:
    // side `cell` from `origin`.
    void mark(const cl::Buffer& hitpoints, const cl::Buffer& hit_stats, uint32_t n, float global_r2,
              const float origin[3], double cell);

    // The chain kernel's arguments after photon_trace's own (from index a), for a pass of
    // photons_per_pass uniform paths; clears the counts.
    void set_trace_args(cl::Kernel& kernel, int a, uint32_t photons_per_pass);
    // Before a pass's first batch.
    void begin_pass();
    // A batch's photons fit: its chains' counts join the pass's.
    void commit_batch();
    // The pass's chains become the next pass's, and its counts join the totals.
    void end_pass();

    // N_states N_U / V_c (Hachisuka and Jensen 2009, Eq. 6 and Sec. 4.2): the photon count that
    // turns the deposited paths' flux into radiance, after `uniform_paths` uniform paths (one per
    // chain and pass). Infinite while no uniform path has been visible: nothing was deposited.
    double effective_emitted(uint64_t uniform_paths) const;

    void save(Checkpoint& ck) const;
    void restore(const Checkpoint& ck);

    size_t device_bytes() const;
    static size_t memory_needed(uint64_t chains, uint64_t hitpoints);

private:
    const DeviceContext& dc_;
    IntegratorStats& stats_;
    uint64_t chains_count_;
    cl::Kernel k_mark_;
    cl::Buffer chains_[2], cache_[2], counts_, grid_info_, seen_; // cache_: each chain's state's photons
    int current_ = 0; // chains_[current_] holds the states the next pass starts from
    uint64_t pending_[CHAIN_COUNTS] = {0, 0, 0, 0};
    uint32_t table_size_ = 0;
    dev::GridInfo grid_{};
};

} // namespace clppm
