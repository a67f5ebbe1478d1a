// Progressive photon mapping (Hachisuka, Ogaki, Jensen 2008): one eye pass storing hit points,
// then refinement passes of photon tracing, grid build, gather and the progressive update.
#pragma once
#include <vector>

#include "integrators/photon_mapping_integrator.h"

namespace clppm {

class PpmIntegrator : public PhotonMappingIntegrator {
public:
    PpmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                  const cl::Program& program, const SecondaryDevices& secondaries = {});
    // The buffers prepare() allocates for `pixels` pixels at settings.spp samples each.
    static IntegratorMemory memory_needed(const RenderSettings& settings, size_t pixels, bool error_estimation = false);

    void prepare() override;
    void run_pass() override;
    Image image() override;
    // Per pixel over its fixed hit points, enabled before prepare(). A pixel's noise bound is the
    // larger of the passes' spread and its fixed samples' spread (the anti-aliasing error fixed
    // hit points never reduce).
    void enable_error_estimation() override;
    ErrorImage error_estimate(double confidence) override;

private:
    // Hit points are state too: on resume they must be the ones the statistics belong to.
    void save_state(Checkpoint& ck) const override;
    void restore_state(const Checkpoint& ck) override;
    void eye_pass();
    void make_error_estimator();

    bool wants_errors_ = false;
    cl::Kernel k_spread_;
    cl::Buffer hit_sample_, sample_y_, spread_; // the sample spread (error_sample_spread)
    uint32_t num_hitpoints_ = 0;
    cl::Buffer pixel_first_, emitted_;
};

} // namespace clppm
