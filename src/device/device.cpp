#include "device/device.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "util/error.h"
#include "util/text.h"

namespace clppm {

namespace {

// Why the device list is empty, as far as can be told: PoCL initialises no device when it cannot
// create its kernel cache (POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl, else $HOME/.cache/pocl),
// which an unwritable or odd HOME causes; otherwise, most likely, no ICD is installed.
std::string empty_device_list_reason() {
    std::string dir;
    const char* pocl = std::getenv("POCL_CACHE_DIR");
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    if (pocl && *pocl) dir = pocl;
    else if (xdg && *xdg) dir = std::string(xdg) + "/pocl";
    else if (home && *home) dir = std::string(home) + "/.cache/pocl";
    if (!dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(dir, ec);
        const std::string probe = dir + "/.clppm_write_test";
        const bool writable = !ec && std::filesystem::is_directory(dir, ec) && std::ofstream(probe).good();
        std::filesystem::remove(probe, ec);
        if (!writable)
            return "PoCL cannot create its kernel cache in " + dir +
                   " (not a writable directory): set POCL_CACHE_DIR or XDG_CACHE_HOME to one";
    }
    return "is an ICD such as pocl-opencl-icd installed?";
}

std::string trim(std::string s) {
    while (!s.empty() && (std::isspace(static_cast<unsigned char>(s.back())) || s.back() == '\0')) s.pop_back();
    size_t i = 0;
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    return s.substr(i);
}

} // namespace

std::string DeviceInfo::type_name() const {
    if (type & CL_DEVICE_TYPE_GPU) return "GPU";
    if (type & CL_DEVICE_TYPE_CPU) return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return "ACCELERATOR";
    return "OTHER";
}

std::vector<DeviceInfo> list_devices() {
    // One listing at a time: the ICD loader (ocl-icd) loads its implementations on the first call,
    // unguarded, and two threads listing at once found no platform in one of them (issue 61).
    static std::mutex listing;
    const std::lock_guard<std::mutex> hold(listing);
    std::vector<DeviceInfo> out;
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error& e) {
        if (e.err() == CL_PLATFORM_NOT_FOUND_KHR) return out; // no ICD installed: an empty list
        throw Error(std::string("OpenCL: cannot list platforms (") + e.what() + ")");
    }
    for (const cl::Platform& p : platforms) {
        std::vector<cl::Device> devices;
        try {
            p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue; // a platform with no devices
        }
        for (const cl::Device& d : devices) {
            DeviceInfo info;
            info.index = static_cast<int>(out.size());
            info.platform = p;
            info.device = d;
            info.platform_name = trim(p.getInfo<CL_PLATFORM_NAME>());
            info.name = trim(d.getInfo<CL_DEVICE_NAME>());
            info.vendor = trim(d.getInfo<CL_DEVICE_VENDOR>());
            info.driver_version = trim(d.getInfo<CL_DRIVER_VERSION>());
            info.opencl_c_version = trim(d.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
            info.type = d.getInfo<CL_DEVICE_TYPE>();
            info.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
            info.global_mem = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
            info.max_alloc = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
            std::string ext = d.getInfo<CL_DEVICE_EXTENSIONS>();
            info.fp64 = ext.find("cl_khr_fp64") != std::string::npos;
            out.push_back(std::move(info));
        }
    }
    return out;
}

std::string DeviceInfo::implementation() const {
    return platform_name.find("Portable Computing Language") != std::string::npos ? "pocl" : platform_name;
}

std::string describe_devices(const std::vector<DeviceInfo>& devices) {
    std::ostringstream os;
    if (devices.empty()) {
        os << "no OpenCL devices found (" << empty_device_list_reason() << ")\n";
        return os.str();
    }
    for (const DeviceInfo& d : devices) {
        os << "[" << d.index << "] " << d.name << "\n"
           << "    platform: " << d.platform_name
           << (d.implementation() != d.platform_name ? " (--device " + d.implementation() + ")" : std::string()) << "\n"
           << "    type: " << d.type_name() << ", compute units: " << d.compute_units
           << ", memory: " << (d.global_mem >> 20) << " MiB (max allocation " << (d.max_alloc >> 20) << " MiB)\n"
           << "    " << d.opencl_c_version << ", driver " << d.driver_version << ", fp64: " << (d.fp64 ? "yes" : "no")
           << "\n";
    }
    return os.str();
}

const DeviceInfo& select_device(const std::vector<DeviceInfo>& devices, const std::string& spec) {
    auto fail = [&](const std::string& why) -> const DeviceInfo& {
        std::ostringstream os;
        os << "--device " << spec << ": " << why << "; available:";
        if (devices.empty()) os << " none (" << empty_device_list_reason() << ")";
        for (const DeviceInfo& d : devices) os << " [" << d.index << "] " << d.name << " (" << d.type_name() << ");";
        std::string msg = os.str();
        if (!msg.empty() && msg.back() == ';') msg.pop_back();
        throw Error(msg);
    };
    if (devices.empty()) return fail("no OpenCL device");
    const std::string s = lower(trim(spec));
    if (s.empty()) return fail("empty device spec");
    if (std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
        size_t idx = std::stoul(s);
        if (idx >= devices.size()) return fail("no device with index " + s);
        return devices[idx];
    }
    if (s == "cpu" || s == "gpu") {
        cl_device_type want = s == "cpu" ? CL_DEVICE_TYPE_CPU : CL_DEVICE_TYPE_GPU;
        for (const DeviceInfo& d : devices)
            if (d.type & want) return d;
        return fail("no " + s + " device");
    }
    for (const DeviceInfo& d : devices)
        if (lower(d.implementation()).find(s) != std::string::npos) return d;
    for (const DeviceInfo& d : devices)
        if (lower(d.name).find(s) != std::string::npos) return d;
    return fail("no implementation or device name matches");
}

DeviceContext::DeviceContext(const DeviceInfo& i) : info(i) {
    try {
        context = cl::Context(info.device);
        queue = cl::CommandQueue(context, info.device, CL_QUEUE_PROFILING_ENABLE);
    } catch (const cl::Error& e) {
        throw Error("OpenCL: cannot create a context on " + info.name + " (" + e.what() + " " +
                    std::to_string(e.err()) + ")");
    }
}

} // namespace clppm
