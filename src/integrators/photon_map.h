// One pass's photons and the hashed grid over them (Hachisuka et al. 2008, Secs. 4.2-4.3), shared
// by every photon-mapping integrator: trace M photons, sort them into the grid, and let a set of
// hit points gather from it. When M photons do not fit the device at once, the pass is traced in
// batches whose gathers add up exactly (fixed-point sums), giving the same image.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/batched_trace.h"
#include "integrators/hash_grid.h"
#include "integrators/integrator_stats.h"
#include "integrators/photon_chains.h"
#include "integrators/render_settings.h"
#include "scene/device_scene.h"

namespace clppm {

// Stored photons per emitted photon a buffer starts out sized for; it grows if a scene stores more.
constexpr uint32_t kStoredPerEmitted = 3;
// The radii of one pass's gathers: PPPM's one radius for every surface hit point (global_r2 > 0;
// else each its own, HitStats.r2), the volume hit points' one radius (volume_r2), the sizes the
// grid's cells are made for (typical, and max, which covers every sphere of the pass), and the
// beams' radius (beam_r2 > 0: kernels/beam.cl gathers for them on a grid of its own).
struct PassRadii {
    float global_r2 = 0;
    float volume_r2 = 0;
    double typical = 0;
    double max = 0;
    float beam_r2 = 0;
};

// Photons traced at once at most: memory stays bounded whatever --photons says, and Ctrl-C is
// answered between batches (about a second each on two CPU cores). Batches do not change the
// image (the flux sums are exact integers).
constexpr uint64_t kMaxBatchPhotons = uint64_t(1) << 22;

class PhotonMap {
public:
    // max_batch_photons bounds the photons traced at once (0: as many as the device memory
    // budget allows; CLPPM_PHOTON_BATCH overrides it, for tests).
    PhotonMap(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
              const cl::Program& program, IntegratorStats& stats, uint64_t max_batch_photons = 0);
    PhotonMap(const PhotonMap&) = delete;
    PhotonMap& operator=(const PhotonMap&) = delete;

    // Pass `pass` (1-based: the RNG streams): traces photons [first, first + count) of the pass's
    // settings.photons, in batches when needed, and for each batch builds the grid (cells sized
    // for radii around radii.typical, no smaller than a quarter of radii.max) and lets the n hit
    // points gather into out with the radii (PassRadii). With count 0, out is cleared.
    void run_pass(uint64_t pass, uint32_t first, uint32_t count, const cl::Buffer& hitpoints, const cl::Buffer& stats,
                  uint32_t n, const PassRadii& radii, const cl::Buffer& out);

    // A further gather over every batch's grid, after the flux gather: `kernel` takes gather's
    // arguments with its own output buffer `out` in place of the PassFlux one (error estimation's
    // Laplacian sums, src/error_estimate.h). An empty kernel turns it off.
    void set_second_gather(const cl::Kernel& kernel, const cl::Buffer& out, const std::string& phase);

    size_t device_bytes() const;

    // With --visual-importance: the chains the photons come from (nullptr without).
    PhotonChains* chains() const { return chains_.get(); }

    // Device memory a pass of settings.photons photons needs at most: both photon buffers within
    // the budget (a quarter of the device), and the grid's table sized for them; with
    // --visual-importance, the chains and the table of cells that `hitpoints` hit points mark.
    static size_t memory_needed(const RenderSettings& settings, const DeviceInfo& device, uint64_t hitpoints);

private:
    void trace(uint64_t pass, uint32_t first, uint32_t count);
    void build_grid(uint32_t stored, const PassRadii& radii);
    void beam_gather(uint32_t stored, uint64_t pass, const cl::Buffer& hitpoints, uint32_t n, float beam_r2,
                     bool accumulate, const cl::Buffer& out);
    void gather(uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n, const PassRadii& radii,
                bool accumulate, const cl::Buffer& out);
    void enqueue_gather(cl::Kernel& kernel, uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats,
                        uint32_t n, const PassRadii& radii, bool accumulate, const cl::Buffer& out,
                        const std::string& phase);
    void measure_coverage(uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                          float global_r2);

    const DeviceContext& dc_;
    const DeviceScene& scene_;
    const RenderSettings& settings_;
    IntegratorStats& stats_;
    cl::Kernel k_photon_, k_gather_, k_coverage_;
    cl::Buffer coverage_; // per hit point: the covered fraction of its gather disc (kernels/disc_coverage.cl)
    uint32_t coverage_capacity_ = 0;
    cl::Buffer open_edges_; // per triangle: its open edges (scene/open_edges.h), made when first measured
    HashGrid grid_;
    // Beams (PassRadii.beam_r2 > 0): the photons sorted again into cells of twice the beams' radius.
    const cl::Program program_;
    cl::Kernel k_beam_;
    std::unique_ptr<HashGrid> beam_grid_;
    cl::Buffer beam_sorted_;
    size_t beam_sorted_bytes_ = 0;
    cl::Kernel k_second_;
    cl::Buffer second_out_;
    std::string second_phase_;
    std::unique_ptr<PhotonChains> chains_;
    BatchedTrace trace_; // last: destroyed first, waiting for the queue
    uint32_t batches_ = 0;
};

} // namespace clppm
