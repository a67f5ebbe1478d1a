// OpenCL platforms and devices: listing, selection by a user's --device spec, and the context and
// queue a render runs on.
#pragma once
#include <string>
#include <vector>

#include "device/cl.h"

namespace clppm {

struct DeviceInfo {
    int index = 0; // position in list_devices(), the number --device takes
    cl::Platform platform;
    cl::Device device;
    std::string platform_name;
    std::string name;
    std::string vendor;
    std::string driver_version;
    std::string opencl_c_version;
    cl_device_type type = 0;
    unsigned compute_units = 0;
    unsigned long long global_mem = 0;
    unsigned long long max_alloc = 0;
    bool fp64 = false;
    std::string type_name() const; // "CPU", "GPU", "ACCELERATOR", "OTHER"
    // The OpenCL implementation, as a --device spec names it: "pocl" for PoCL (whose platform is
    // "Portable Computing Language"), else the platform's name ("Intel(R) OpenCL", "NVIDIA CUDA").
    std::string implementation() const;
};

// Every device of every platform, in a stable order (platform order, then device order).
std::vector<DeviceInfo> list_devices();

// A human-readable table of list_devices() for --list-devices.
std::string describe_devices(const std::vector<DeviceInfo>& devices);

// Resolves one --device spec: an index as listed, "cpu", "gpu", or a case-insensitive substring
// of an implementation's name (the first device of the first implementation it names: "pocl",
// "intel", "nvidia"), else of a device's name. Implementations come first because device names
// repeat the processor's: PoCL calls its CPU device "pthread-skylake-avx512-Intel(R) Xeon(R) ...",
// so "intel" picked PoCL wherever it was listed first. Throws Error naming the spec and listing
// what exists.
const DeviceInfo& select_device(const std::vector<DeviceInfo>& devices, const std::string& spec);

// Device, context and in-order queue (profiling enabled) used by one render.
struct DeviceContext {
    DeviceInfo info;
    cl::Context context;
    cl::CommandQueue queue;
    explicit DeviceContext(const DeviceInfo& info);
};

} // namespace clppm
