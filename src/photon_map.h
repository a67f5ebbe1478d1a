// One pass's photons and the hashed grid over them (Hachisuka et al. 2008, Secs. 4.2-4.3), shared
// by every photon-mapping integrator: trace M photons, sort them into the grid, and let a set of
// hit points gather from it.
#pragma once
#include <cstdint>

#include "cl.h"
#include "device.h"
#include "integrator.h"
#include "render_scene.h"
#include "render_settings.h"

namespace clppm {

class PhotonMap {
public:
    PhotonMap(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
              const cl::Program& program, IntegratorStats& stats);

    // Traces settings.photons photons for pass `pass` (1-based; the RNG stream). Stored hits that
    // outgrow the buffer make it grow and the pass be traced again with the same streams.
    void trace(uint64_t pass);

    // Builds the grid with cells sized for hit point radii around `typical_radius`, no smaller
    // than a quarter of `max_radius` (so no hit point visits more than 9^3 cells).
    void build_grid(double typical_radius, double max_radius);

    // Each of n hit points gathers the photons within its radius (stats[i].r2, or global_r2 when
    // > 0) into out[i].
    void gather(const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n, float global_r2,
                const cl::Buffer& out);

    uint32_t stored() const { return stored_; }
    size_t device_bytes() const;

private:
    const DeviceContext& dc_;
    const DeviceScene& scene_;
    const RenderSettings& settings_;
    IntegratorStats& stats_;
    cl::Kernel k_photon_, k_count_, k_scan_, k_scatter_, k_gather_;
    cl::Buffer photons_, sorted_, counter_, grid_info_, counts_, starts_;
    uint32_t capacity_ = 0;
    uint32_t stored_ = 0;
    uint32_t table_size_ = 0;
};

// Explicit direct lighting: one light sample per hit point, added to stats[i].direct.
void enqueue_direct_light(const DeviceContext& dc, const DeviceScene& scene, cl::Kernel& kernel, uint64_t seed,
                          uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                          IntegratorStats& istats);

// Twice the median pixel footprint of the hit points, kept within [1e-6, 0.05] of the scene's
// bounding diameter: the default initial radius.
double initial_radius_heuristic(std::vector<float> footprints, double scene_radius);

} // namespace clppm
