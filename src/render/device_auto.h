// --device auto: the device a render is fastest on, by measurement (issue 58). Each candidate (one
// device of each implementation and kind: PoCL's CPU device, Intel's, a GPU) renders the job
// itself for a moment, without outputs, and the render runs on the one with the most passes per
// second. The default device (render/device_choice.h) is kept unless another is more than
// kAutoMargin faster, so that the choice does not flip with noise, and the choice is kept in
// clppm's cache (device/cache_dir.h) for the same devices, scene file, integrator and size, so that
// later renders are not measured again and give the same image.
#pragma once
#include <string>
#include <vector>

#include "device/device.h"
#include "render/render_log.h"
#include "render/render_options.h"

namespace clppm {

constexpr double kAutoMargin = 0.10;  // how much faster than the default a device must be
constexpr double kTrialSeconds = 0.5; // rendering each candidate is timed for at least this long
constexpr uint64_t kTrialPasses = 2;  // ... and at least this many passes (after one untimed)

struct DeviceTrial {
    DeviceInfo device;
    uint64_t passes = 0; // timed passes
    double seconds = 0;  // their wall time
    double passes_per_second() const { return seconds > 0 ? double(passes) / seconds : 0.0; }
};

// Whether the --device specs ask for a measured choice ("auto", alone).
bool wants_auto_device(const std::vector<std::string>& specs);

// The candidates among `devices`: the first of each (implementation, name), in list order.
std::vector<DeviceInfo> auto_candidates(const std::vector<DeviceInfo>& devices);

// Picks among trials: the default device's unless another's rate is more than kAutoMargin above it.
const DeviceTrial& pick_trial(const std::vector<DeviceTrial>& trials, const DeviceInfo& default_device);

// The device for the render `options` describes (their --device is "auto"), measured or from the
// cache; says which and why through `log`. Throws Error with several MPI processes (each would
// measure its own machine, and they must build the same render) and when no device is there.
DeviceInfo auto_device(const RenderOptions& options, const std::vector<DeviceInfo>& devices, RenderLog& log);

} // namespace clppm
