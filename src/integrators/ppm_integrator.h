// Progressive photon mapping (Hachisuka, Ogaki, Jensen 2008): one eye pass storing hit points,
// then refinement passes of photon tracing, grid build, gather and the progressive update.
#pragma once
#include <memory>
#include <vector>

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

    // The buffers prepare() allocates for `pixels` pixels at settings.spp samples each.
    static IntegratorMemory memory_needed(const RenderSettings& settings, size_t pixels);

private:
    void eye_pass();
    void update();

    const DeviceContext& dc_;
    const DeviceScene& scene_;
    RenderSettings settings_;
    std::unique_ptr<PhotonPasses> photons_;
    cl::Kernel k_eye_, k_direct_, k_update_, k_film_;

    uint32_t num_pixels_ = 0;
    uint32_t num_hitpoints_ = 0;
    cl::Buffer hitpoints_, stats_buf_, passflux_, pixel_first_, emitted_, image_buf_, radius_partials_;
    double typical_radius_ = 0; // mean R over hit points: sizes the next grid's cells
    double max_radius_ = 0;
};

} // namespace clppm
