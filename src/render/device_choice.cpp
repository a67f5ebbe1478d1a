#include "render/device_choice.h"

#include "util/error.h"

namespace clppm {

std::vector<DeviceInfo> choose_devices(const std::vector<std::string>& specs, const std::vector<DeviceInfo>& devices) {
    std::vector<DeviceInfo> chosen;
    for (const std::string& spec : specs) {
        if (spec == "all") {
            if (devices.empty()) select_device(devices, spec); // throws: no device
            for (const DeviceInfo& d : devices) chosen.push_back(d);
            continue;
        }
        const DeviceInfo& d = select_device(devices, spec);
        for (const DeviceInfo& c : chosen)
            if (c.index == d.index)
                throw Error("--device " + spec + ": device [" + std::to_string(d.index) + "] " + d.name +
                            " is given twice");
        chosen.push_back(d);
    }
    if (!chosen.empty()) return chosen;
    for (const DeviceInfo& d : devices)
        if (d.type & CL_DEVICE_TYPE_GPU) return {d};
    // Several CPU implementations (PoCL and Intel's runtime): PoCL, which was as fast or faster for
    // every integrator (bench/RESULTS.md, "Intel's CPU runtime beside PoCL"), whichever the
    // loader lists first.
    for (const DeviceInfo& d : devices)
        if ((d.type & CL_DEVICE_TYPE_CPU) && d.implementation() == "pocl") return {d};
    return {select_device(devices, "0")};
}

} // namespace clppm
