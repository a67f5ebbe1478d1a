// The devices a render runs on, the first of them primary: every --device spec in order ("all":
// every device), else the first GPU, else PoCL's CPU device, else device 0. A device named twice
// is an error.
#pragma once
#include <string>
#include <vector>

#include "device/device.h"

namespace clppm {

std::vector<DeviceInfo> choose_devices(const std::vector<std::string>& specs, const std::vector<DeviceInfo>& devices);

} // namespace clppm
