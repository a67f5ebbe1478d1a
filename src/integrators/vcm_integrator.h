// Vertex connection and merging (Georgiev et al. 2012) and bidirectional path tracing, its
// connections-only case: per pass, one light sub-path and one camera sub-path per pixel
// (kernels/vcm.cl), the merging radius shrinking as PPPM's (Knaus and Zwicker 2011, Eq. 19).
// Every pass adds one unbiased-in-the-limit sample per pixel to a running sum, as the path tracer.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "integrators/batched_trace.h"
#include "integrators/device_fan_out.h"
#include "integrators/hash_grid.h"
#include "integrators/pixel_sum_integrator.h"
#include "integrators/render_settings.h"
#include "scene/device_scene.h"
#include "vcm_mis.h"

namespace clppm {

class VcmIntegrator : public PixelSumIntegrator {
public:
    // With secondaries, every device traces all light sub-paths and the camera sub-paths of a share
    // of the pixels (by its measured speed); the shares' sums join the primary's.
    VcmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                  const cl::Program& program, const SecondaryDevices& secondaries = {});
    ~VcmIntegrator() override;
    // The per-pixel buffers prepare() (and enable_error_estimation()) allocate for `pixels` pixels.
    static IntegratorMemory memory_needed(size_t pixels, bool error_estimation = false);
    // The light vertex buffers and grid a pass over `pixels` light sub-paths starts with (they are
    // batched to stay within a quarter of the device's memory).
    static size_t light_vertex_bytes(size_t pixels, const DeviceInfo& device);

    void prepare() override;
    void run_pass() override;
    // The sum and the merging radius.
    void save(Checkpoint& ck) override;
    void restore(const Checkpoint& ck) override;

    // The radius this pass merges with (world units).
    double radius() const;

private:
    struct Worker;
    // Pass `pass` for the camera sub-paths of pixels [first, first + count): the light sub-paths and
    // batches, then `out` (a running sum per pixel) gets each pixel's sample added.
    void render(uint64_t pass, uint32_t first, uint32_t count, const cl::Buffer& out);
    dev::VcmPass pass_constants(uint64_t pass) const;
    void trace_light(const dev::VcmPass& vp, uint32_t first, uint32_t count);
    // Several devices: the rank's pixels between them, their samples joined into the sum.
    void render_on_devices(uint64_t pass, const PixelRanges& ranges);

    uint32_t mode_;
    cl::Kernel k_light_, k_camera_, k_footprint_;
    HashGrid grid_;
    cl::Buffer pass_sum_, splat_, path_last_;
    std::unique_ptr<BatchedTrace> trace_; // the light sub-paths' vertices
    double r2_ = 0;                       // this pass's squared merging radius
    double area_scale_ = 1;               // R^2 of the scene's bounding sphere: the kernels' unit of area
    std::vector<std::unique_ptr<Worker>> workers_;
    DeviceFanOut fan_out_{{1}}; // the pixels of this rank's range between its devices
};

} // namespace clppm
