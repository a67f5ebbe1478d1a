// Progressive photon mapping (Hachisuka, Ogaki, Jensen 2008): one eye pass storing hit points,
// then refinement passes of photon tracing, grid build, gather and the progressive update.
#pragma once
#include <memory>
#include <vector>

#include "integrator.h"
#include "photon_passes.h"

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

// Runs ppm_update (kernels/ppm_update.cl) over n hit points and returns (mean, max) of R after it.
std::pair<double, double> enqueue_ppm_update(const DeviceContext& dc, cl::Kernel& kernel, const cl::Buffer& passflux,
                                             const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                                             double alpha, const cl::Buffer& radius_partials, IntegratorStats& istats);

// Bytes of the per-group radius partials enqueue_ppm_update needs for n hit points.
size_t radius_partials_bytes(uint32_t n);

// Reads a float4 image buffer back into an Image.
Image read_image(const DeviceContext& dc, const cl::Buffer& buffer, unsigned width, unsigned height);

} // namespace clppm
