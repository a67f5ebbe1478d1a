// Progressive photon mapping (Hachisuka, Ogaki, Jensen 2008): one eye pass storing hit points,
// then refinement passes of photon tracing, grid build, gather and the progressive update.
#pragma once
#include <vector>

#include "integrator.h"

namespace clppm {

class PpmIntegrator : public IntegratorBase {
public:
    PpmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                  const cl::Program& program);
    std::string name() const override { return "ppm"; }
    void prepare() override;
    void run_pass() override;
    Image image() override;

    // The initial radius heuristic: twice the median pixel footprint of the hit points, kept
    // within [1e-6, 0.05] of the scene's bounding diameter.
    static double initial_radius(std::vector<float> footprints, double scene_radius);

private:
    void eye_pass();
    void trace_photons();
    void build_grid();
    void gather_and_update();

    const DeviceContext& dc_;
    const DeviceScene& scene_;
    RenderSettings settings_;
    cl::Kernel k_eye_, k_photon_, k_count_, k_scan_, k_scatter_, k_gather_, k_direct_, k_update_, k_film_;

    uint32_t num_pixels_ = 0;
    uint32_t num_hitpoints_ = 0;
    cl::Buffer hitpoints_, stats_buf_, passflux_, pixel_first_, emitted_, image_buf_, radius_partials_;
    cl::Buffer photons_, sorted_, counter_, grid_info_, counts_, starts_;
    uint32_t photon_capacity_ = 0;
    uint32_t photons_this_pass_ = 0;
    uint32_t table_size_ = 0;
    double cell_radius_ = 0;  // radius the next grid's cells are sized for
    double max_radius_ = 0;
};

} // namespace clppm
