// The interface every integrator offers the render loop: a pass is the unit of work
// (SmallVCM's RunIteration), and the image can be taken at any pass boundary. It holds what every
// integrator has (the device, the scene on it, the settings, the program, the statistics and the
// error estimator); integrators/photon_mapping_integrator.h and pixel_sum_integrator.h add what
// each family shares. The interface knows no concrete integrator: integrators/integrator_table.h
// makes them.
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/error_estimate.h"
#include "integrators/error_image.h"
#include "integrators/integrator_stats.h"
#include "integrators/render_settings.h"
#include "io/checkpoint.h"
#include "io/image_io.h"
#include "scene/device_scene.h"

namespace clppm {

class IntegratorBase {
public:
    virtual ~IntegratorBase() = default;
    IntegratorBase(const IntegratorBase&) = delete;
    IntegratorBase& operator=(const IntegratorBase&) = delete;

    // Its row's name in integrators/integrator_table.h.
    std::string name() const { return settings_.integrator; }
    // Everything before the first refinement pass (PPM: the eye pass).
    virtual void prepare() = 0;
    // One pass, or, where the integrator batches passes and allow_passes() allowed more, up to
    // that many in one launch (the path tracer: the same image bit for bit, fewer launches).
    virtual void run_pass() = 0;
    // The most passes the next run_pass() may run (at least 1; 1 until said otherwise).
    void allow_passes(uint64_t n) { pass_allowance_ = n > 0 ? n : 1; }
    virtual Image image() = 0;
    const IntegratorStats& stats() const { return stats_; }

    // The progressive state after the last pass, and its restoration after prepare(): the
    // render then continues exactly as if it had never stopped.
    virtual void save(Checkpoint& ck);
    virtual void restore(const Checkpoint& ck);

    // Progressive error estimation (integrators/error_estimate.h), for the integrators whose row
    // says so. enable_error_estimation() before prepare() covers the whole render;
    // error_estimate() gives the per-pixel bounds after the last pass at `confidence` in (0, 1).
    // Both throw Error where the integrator has none.
    virtual void enable_error_estimation();
    virtual ErrorImage error_estimate(double confidence);
    // The relative variance of a scale common to the whole image that the error statistics'
    // passes cannot see (ErrorEstimator::estimate); 0 unless an integrator has one.
    virtual double normalization_variance() const { return 0; }

protected:
    IntegratorBase(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                   const cl::Program& program);
    // The error statistics into the checkpoint, and back: a checkpoint saved without them starts
    // the estimate over from `source` (the hit statistics, or the path tracer's running sums).
    void save_error_stats(Checkpoint& ck) const;
    void restore_error_stats(const Checkpoint& ck, const cl::Buffer& source);

    const DeviceContext& dc_;
    const DeviceScene& scene_;
    const RenderSettings settings_;
    const cl::Program program_;
    const uint32_t num_pixels_;
    IntegratorStats stats_;
    std::unique_ptr<ErrorEstimator> errors_; // when estimating
    uint64_t pass_allowance_ = 1;            // allow_passes()
};

// Device memory an integrator will allocate for its own buffers (hit points or per-pixel
// statistics, film, error estimation), worked out before anything is allocated. Each integrator
// reports its own (a static memory_needed beside its constructor).
struct IntegratorMemory {
    size_t bytes = 0;
    size_t largest_buffer = 0;
};

// Further devices a photon-mapping integrator shares its photons with, and how to build their
// program (the primary's program file and options).
struct SecondaryDevices {
    std::vector<DeviceInfo> devices;
    std::string program_file, build_options;
};

} // namespace clppm
