// Progressive photon mapping (Hachisuka, Ogaki, Jensen 2008): one eye pass storing hit points,
// then refinement passes of photon tracing, grid build, gather and the progressive update.
#pragma once
#include <memory>
#include <vector>

#include "integrators/error_estimate.h"
#include "integrators/integrator.h"
#include "integrators/photon_passes.h"
#include "integrators/render_settings.h"
#include "scene/device_scene.h"

namespace clppm {

class PpmIntegrator : public IntegratorBase {
public:
    PpmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                  const cl::Program& program, const SecondaryDevices& secondaries = {});
    std::string name() const override { return "ppm"; }
    void prepare() override;
    void run_pass() override;
    Image image() override;
    void save(Checkpoint& ck) override;
    void restore(const Checkpoint& ck) override;
    // Progressive error estimation per pixel over its fixed hit points, enabled before prepare().
    // A pixel's noise bound is the larger of the passes' spread and its fixed samples' spread
    // (the anti-aliasing error fixed hit points never reduce).
    bool estimates_error() const override { return true; }
    void enable_error_estimation() override;
    ErrorImage error_estimate(double confidence) override;

    // The buffers prepare() allocates for `pixels` pixels at settings.spp samples each.
    static IntegratorMemory memory_needed(const RenderSettings& settings, size_t pixels, bool error_estimation = false);

private:
    void eye_pass();
    void update();
    void make_error_estimator();

    const DeviceContext& dc_;
    const DeviceScene& scene_;
    RenderSettings settings_;
    std::unique_ptr<PhotonPasses> photons_;
    cl::Kernel k_eye_, k_direct_, k_update_, k_film_;
    cl::Program program_; // for the error estimation kernels
    bool wants_errors_ = false;
    std::unique_ptr<ErrorEstimator> errors_;
    cl::Kernel k_spread_;
    cl::Buffer hit_sample_, sample_y_, spread_; // the sample spread (error_sample_spread)

    uint32_t num_pixels_ = 0;
    uint32_t num_hitpoints_ = 0;
    cl::Buffer hitpoints_, stats_buf_, passflux_, pixel_first_, emitted_, image_buf_, radius_partials_;
    double typical_radius_ = 0; // mean R over hit points: sizes the next grid's cells
    double max_radius_ = 0;
};

} // namespace clppm
