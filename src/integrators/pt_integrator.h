// Path tracing on the same scene kernels: one sample per pixel per pass, for equal-time
// comparisons with photon mapping and for cross-checking diffuse scenes.
#pragma once
#include <string>
#include <vector>

#include "integrators/pixel_sum_integrator.h"
#include "scene/scene.h"
#include "scene/scene_features.h"

namespace clppm {

class PtIntegrator : public PixelSumIntegrator {
public:
    // The path tracer renders on the first device alone: `secondaries` must be empty.
    PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                 const cl::Program& program, const SecondaryDevices& secondaries = {});
    // The buffers prepare() (and enable_error_estimation()) allocate for `pixels` pixels.
    static IntegratorMemory memory_needed(size_t pixels, bool error_estimation = false);
    // Light it never finds: a point, spot or directional light seen through smooth glass or a
    // mirror (a caustic) is a path of two delta events it never samples.
    static std::vector<std::string> warnings(const Scene& scene, const SceneFeatures& features);

    void prepare() override;
    void run_pass() override;
    void save(Checkpoint& ck) override;
    void restore(const Checkpoint& ck) override;

protected:
    bool sobol_passes() const override;

private:
    static uint32_t screen_layout_log2(const RenderSettings& settings, const dev::Camera& camera);

    // A launch of the path tracer's passes is meant to take about this long: a pass of a small
    // image is over in a few milliseconds, and each launch costs PoCL about half of one (its worker
    // threads woken and the tail of the pass left to one of them), measured 15% of the render at
    // 128x128 (bench/RESULTS.md, "Several passes to a launch").
    static constexpr double kLaunchSeconds = 0.02;
    static constexpr uint64_t kMaxBatch = 64;
    // kMaxBatch, or the CLPPM_PASS_BATCH environment variable's cap (1: a launch a pass; for
    // measuring the batches, which never change the image).
    static uint64_t max_batch();

    cl::Kernel k_trace_;
    uint64_t batch_ = 1;                     // passes the next launch may run, from the last launch's time a pass
    uint32_t screen_log2_ = SOBOL_PER_PIXEL; // --sampler zsobol's L, else each pixel's own sequence
};

} // namespace clppm
