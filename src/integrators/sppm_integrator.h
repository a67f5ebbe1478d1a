// Stochastic progressive photon mapping (Hachisuka and Jensen 2009) and probabilistic PPM (Knaus
// and Zwicker 2011): a new eye sample per pixel every pass (anti-aliasing, depth of field, every
// specular choice sampled), statistics per pixel, memory proportional to the pixel count.
#pragma once
#include <memory>

#include "integrators/error_estimate.h"
#include "integrators/integrator.h"
#include "integrators/photon_passes.h"
#include "integrators/render_settings.h"
#include "scene/device_scene.h"

namespace clppm {

class SppmIntegrator : public IntegratorBase {
public:
    SppmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                   const cl::Program& program, const SecondaryDevices& secondaries = {});
    std::string name() const override { return probabilistic_ ? "pppm" : "sppm"; }
    void prepare() override;
    void run_pass() override;
    Image image() override;
    void save(Checkpoint& ck) override;
    void restore(const Checkpoint& ck) override;

    // Progressive error estimation, from the next pass on. Off unless asked for, so a render
    // without it launches nothing more.
    bool estimates_error() const override { return true; }
    void enable_error_estimation() override;
    ErrorImage error_estimate(double confidence) override;

    // The buffers prepare() (and enable_error_estimation()) allocate for `pixels` pixels.
    static IntegratorMemory memory_needed(size_t pixels, bool error_estimation);

private:
    void eye_pass(uint64_t pass);
    double power_per_photon() const { return double(scene_.info.total_power) / double(settings_.photons); }

    const DeviceContext& dc_;
    const DeviceScene& scene_;
    RenderSettings settings_;
    bool probabilistic_;
    std::unique_ptr<PhotonPasses> photons_;
    cl::Program program_; // for the error estimation kernels
    std::unique_ptr<ErrorEstimator> errors_;
    cl::Kernel k_eye_, k_emission_, k_direct_, k_update_, k_accumulate_, k_film_;
    uint32_t num_pixels_ = 0;
    cl::Buffer hitpoints_, sample_emission_, stats_buf_, passflux_, image_buf_, radius_partials_;
    double r2_ = 0;             // PPPM: this pass's radius squared
    double typical_radius_ = 0; // SPPM: mean R over pixels, sizing the next grid
    double max_radius_ = 0;
};

} // namespace clppm
