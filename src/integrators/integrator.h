// The interface every integrator offers the render loop: a pass is the unit of work
// (SmallVCM's RunIteration), and the image can be taken at any pass boundary. The interface knows
// no concrete integrator: integrators/integrator_factory.h makes them.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "device/device.h"
#include "integrators/error_image.h"
#include "integrators/integrator_stats.h"
#include "io/checkpoint.h"
#include "io/image_io.h"

namespace clppm {

class IntegratorBase {
public:
    virtual ~IntegratorBase() = default;
    virtual std::string name() const = 0;
    // Everything before the first refinement pass (PPM: the eye pass).
    virtual void prepare() = 0;
    virtual void run_pass() = 0;
    virtual Image image() = 0;
    const IntegratorStats& stats() const { return stats_; }

    // The progressive state after the last pass, and its restoration after prepare(): the
    // render then continues exactly as if it had never stopped.
    virtual void save(Checkpoint& ck);
    virtual void restore(const Checkpoint& ck);

    // Progressive error estimation (integrators/error_estimate.h), for the integrators that offer
    // it. enable_error_estimation() before prepare() covers the whole render; error_estimate()
    // gives the per-pixel bounds after the last pass at `confidence` in (0, 1). Both throw Error
    // where estimates_error() is false.
    virtual bool estimates_error() const { return false; }
    virtual void enable_error_estimation();
    virtual ErrorImage error_estimate(double confidence);

protected:
    IntegratorStats stats_;
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
