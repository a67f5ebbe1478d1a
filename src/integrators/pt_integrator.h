// Path tracing on the same scene kernels: one sample per pixel per pass, for equal-time
// comparisons with photon mapping and for cross-checking diffuse scenes.
#pragma once
#include "integrators/integrator.h"
#include "integrators/render_settings.h"
#include "scene/device_scene.h"

namespace clppm {

class PtIntegrator : public IntegratorBase {
public:
    PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                 const cl::Program& program);
    std::string name() const override { return "pt"; }
    void prepare() override;
    void run_pass() override;
    Image image() override;
    void save(Checkpoint& ck) override;
    void restore(const Checkpoint& ck) override;

    // The buffers prepare() allocates for `pixels` pixels.
    static IntegratorMemory memory_needed(size_t pixels);

private:
    const DeviceContext& dc_;
    const DeviceScene& scene_;
    RenderSettings settings_;
    cl::Kernel k_trace_, k_film_;
    cl::Buffer accum_, image_buf_;
    uint32_t num_pixels_ = 0;
};

} // namespace clppm
