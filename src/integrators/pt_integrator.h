// Path tracing on the same scene kernels: one sample per pixel per pass, for equal-time
// comparisons with photon mapping and for cross-checking diffuse scenes.
#pragma once
#include <memory>
#include <vector>

#include "integrators/error_estimate.h"
#include "integrators/integrator.h"
#include "integrators/render_settings.h"
#include "integrators/work_balance.h"
#include "scene/device_scene.h"
#include "scene/scene.h"
#include "scene/scene_features.h"

namespace clppm {

class PtIntegrator : public IntegratorBase {
public:
    // The path tracer renders on the first device alone: `secondaries` must be empty.
    PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                 const cl::Program& program, const SecondaryDevices& secondaries = {});
    std::string name() const override { return "pt"; }
    void prepare() override;
    void run_pass() override;
    Image image() override;
    void save(Checkpoint& ck) override;
    void restore(const Checkpoint& ck) override;
    // Progressive error estimation from the spread of the passes' samples (no bias: the path
    // tracer is unbiased), from the next pass on.
    bool estimates_error() const override { return true; }
    void enable_error_estimation() override;
    ErrorImage error_estimate(double confidence) override;

    // The buffers prepare() (and enable_error_estimation()) allocate for `pixels` pixels.
    static IntegratorMemory memory_needed(size_t pixels, bool error_estimation = false);

    // Light it never finds: a point, spot or directional light seen through smooth glass or a
    // mirror (a caustic) is a path of two delta events it never samples.
    static std::vector<std::string> warnings(const Scene& scene, const SceneFeatures& features);

private:
    WorkBalance balance_; // this rank's seconds against its pixels, for the ranks' split

    const DeviceContext& dc_;
    const DeviceScene& scene_;
    RenderSettings settings_;
    cl::Kernel k_trace_, k_film_;
    cl::Program program_; // for the error estimation kernels
    cl::Buffer accum_, image_buf_;
    std::unique_ptr<ErrorEstimator> errors_;
    uint32_t num_pixels_ = 0;
};

} // namespace clppm
