// --device SPEC (device/device.h, select_device) among several OpenCL implementations, on a made-up
// device list: implementations by name first, then devices by name, so that "intel" names Intel's
// runtime even where PoCL, whose CPU device's name repeats the processor's, is listed first.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "device/device.h"
#include "render/device_choice.h"
#include "util/error.h"

using namespace clppm;

namespace {

DeviceInfo device(int index, const std::string& platform, const std::string& name, cl_device_type type) {
    DeviceInfo d;
    d.index = index;
    d.platform_name = platform;
    d.name = name;
    d.type = type;
    return d;
}

std::vector<DeviceInfo> three_implementations() {
    return {device(0, "Portable Computing Language", "pthread-skylake-avx512-Intel(R) Xeon(R) Processor",
                   CL_DEVICE_TYPE_CPU),
            device(1, "Intel(R) OpenCL", "Intel(R) Xeon(R) Processor", CL_DEVICE_TYPE_CPU),
            device(2, "NVIDIA CUDA", "NVIDIA H100 80GB HBM3", CL_DEVICE_TYPE_GPU)};
}

} // namespace

TEST(DeviceSelect, ImplementationsByName) {
    const auto devices = three_implementations();
    EXPECT_EQ(devices[0].implementation(), "pocl");
    EXPECT_EQ(devices[1].implementation(), "Intel(R) OpenCL");
    EXPECT_EQ(select_device(devices, "intel").index, 1) << "PoCL's device name has Intel in it too";
    EXPECT_EQ(select_device(devices, "Intel").index, 1);
    EXPECT_EQ(select_device(devices, "pocl").index, 0);
    EXPECT_EQ(select_device(devices, "PoCL").index, 0);
    EXPECT_EQ(select_device(devices, "nvidia").index, 2);
}

TEST(DeviceSelect, DevicesByNameIndexAndType) {
    const auto devices = three_implementations();
    EXPECT_EQ(select_device(devices, "xeon").index, 0) << "no implementation is called xeon: the first device";
    EXPECT_EQ(select_device(devices, "h100").index, 2);
    EXPECT_EQ(select_device(devices, "1").index, 1);
    EXPECT_EQ(select_device(devices, "gpu").index, 2);
    EXPECT_EQ(select_device(devices, "cpu").index, 0);
}

TEST(DeviceSelect, NothingMatchesIsAnErrorListingTheDevices) {
    const auto devices = three_implementations();
    try {
        select_device(devices, "radeon");
        FAIL() << "no error";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("--device radeon: no implementation or device name matches"), std::string::npos) << m;
        EXPECT_NE(m.find("[1] Intel(R) Xeon(R) Processor (CPU)"), std::string::npos) << m;
    }
}

TEST(DeviceSelect, WithoutASpecAGpuElsePoclsCpu) {
    auto devices = three_implementations();
    EXPECT_EQ(choose_devices({}, devices).at(0).index, 2);
    devices.pop_back(); // no GPU
    std::swap(devices[0], devices[1]);
    devices[0].index = 0, devices[1].index = 1; // Intel's runtime listed first
    EXPECT_EQ(choose_devices({}, devices).at(0).implementation(), "pocl");
    devices.pop_back(); // Intel's alone
    EXPECT_EQ(choose_devices({}, devices).at(0).implementation(), "Intel(R) OpenCL");
}
