// --device SPEC (device/device.h, select_device) among several OpenCL implementations, on a made-up
// device list: implementations by name first, then devices by name, so that "intel" names Intel's
// runtime even where PoCL, whose CPU device's name repeats the processor's, is listed first.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "device/device.h"
#include "render/device_choice.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;

namespace {

DeviceInfo device(int index, const std::string& platform, const std::string& name, cl_device_type type) {
    return test::fake_device(index, platform, name, type);
}

std::vector<DeviceInfo> three_implementations() {
    return {device(0, "Portable Computing Language", "pthread-skylake-avx512-Intel(R) Xeon(R) Processor",
                   CL_DEVICE_TYPE_CPU),
            device(1, "Intel(R) OpenCL", "Intel(R) Xeon(R) Processor", CL_DEVICE_TYPE_CPU),
            device(2, "NVIDIA CUDA", "NVIDIA H100 80GB HBM3", CL_DEVICE_TYPE_GPU)};
}

} // namespace

TEST(DeviceSelect, ImplementationsThenDevicesByName) {
    const auto devices = three_implementations();
    EXPECT_EQ(devices[0].implementation(), "pocl");
    EXPECT_EQ(devices[1].implementation(), "Intel(R) OpenCL");
    const struct {
        const char* spec;
        int index;
        const char* why;
    } cases[] = {
        {"intel", 1, "PoCL's device name has Intel in it too"},
        {"Intel", 1, "any case"},
        {"pocl", 0, "PoCL's short name"},
        {"PoCL", 0, "any case"},
        {"nvidia", 2, "a platform's name"},
        {"xeon", 0, "no implementation is called xeon: the first device"},
        {"h100", 2, "a device's name"},
        {"1", 1, "an index"},
        {"gpu", 2, "a type"},
        {"cpu", 0, "a type"},
    };
    for (const auto& c : cases) EXPECT_EQ(select_device(devices, c.spec).index, c.index) << c.spec << ": " << c.why;
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
