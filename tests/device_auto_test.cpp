// --device auto (render/device_auto.h): which devices it measures, how it picks among their rates,
// and what it says. The measurement itself among two implementations is in
// tests/implementations_test.cpp, which runs where Intel's CPU runtime is installed beside PoCL.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "device/device.h"
#include "render/device_auto.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;
using namespace clppm::test;

namespace {

DeviceInfo device(int index, const std::string& platform, const std::string& name, cl_device_type type) {
    return test::fake_device(index, platform, name, type);
}

const std::string kPocl = "Portable Computing Language", kPoclCpu = "pthread-skylake-avx512-Intel(R) Xeon(R) Processor";

DeviceTrial trial(const DeviceInfo& d, double passes_per_second) {
    DeviceTrial t{d};
    t.passes = uint64_t(passes_per_second * 10);
    t.seconds = 10;
    return t;
}

} // namespace

TEST(DeviceAuto, OnlyAutoAloneAsksForAMeasurement) {
    EXPECT_TRUE(wants_auto_device({"auto"}));
    EXPECT_FALSE(wants_auto_device({}));
    EXPECT_FALSE(wants_auto_device({"pocl"}));
    try {
        wants_auto_device({"auto", "0"});
        FAIL() << "auto with another spec was accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "--device auto: measures the devices to pick one; give it alone");
    }
}

// PoCL's two pthread devices (POCL_DEVICES="pthread pthread") are one candidate; each
// implementation and each GPU is one.
TEST(DeviceAuto, OneCandidateForEachImplementationAndDevice) {
    const std::vector<DeviceInfo> devices = {
        device(0, kPocl, kPoclCpu, CL_DEVICE_TYPE_CPU), device(1, kPocl, kPoclCpu, CL_DEVICE_TYPE_CPU),
        device(2, "Intel(R) OpenCL", "Intel(R) Xeon(R) Processor", CL_DEVICE_TYPE_CPU),
        device(3, "NVIDIA CUDA", "NVIDIA H100 80GB HBM3", CL_DEVICE_TYPE_GPU)};
    const std::vector<DeviceInfo> c = auto_candidates(devices);
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c[0].index, 0);
    EXPECT_EQ(c[1].index, 2);
    EXPECT_EQ(c[2].index, 3);
}

// The default device keeps the render unless another is more than kAutoMargin faster: a choice
// that flipped with noise would change the image from one run to the next.
TEST(DeviceAuto, TheDefaultIsKeptWithinTheMargin) {
    const DeviceInfo pocl = device(0, kPocl, kPoclCpu, CL_DEVICE_TYPE_CPU),
                     intel = device(1, "Intel(R) OpenCL", "Intel(R) Xeon(R) Processor", CL_DEVICE_TYPE_CPU);
    EXPECT_EQ(pick_trial({trial(pocl, 100), trial(intel, 109)}, pocl).device.index, 0);
    EXPECT_EQ(pick_trial({trial(pocl, 100), trial(intel, 111)}, pocl).device.index, 1);
    EXPECT_EQ(pick_trial({trial(intel, 111), trial(pocl, 100)}, pocl).device.index, 1);
    EXPECT_EQ(pick_trial({trial(pocl, 100), trial(intel, 50)}, pocl).device.index, 0);
    // The default could not render the scene (no trial): the fastest of the rest.
    const DeviceInfo gpu = device(2, "NVIDIA CUDA", "NVIDIA H100 80GB HBM3", CL_DEVICE_TYPE_GPU);
    EXPECT_EQ(pick_trial({trial(intel, 100), trial(gpu, 900)}, pocl).device.index, 2);
}

// With one candidate there is nothing to measure, and the render says so.
TEST(DeviceAuto, OneDeviceIsNotMeasured) {
    const std::string dir = make_temp_dir("device_auto");
    std::string out;
    // PoCL alone, whatever else the machine has installed: an ICD folder naming PoCL only.
    ASSERT_EQ(
        run_command("mkdir -p '" + dir + "/vendors' && cp /etc/OpenCL/vendors/pocl.icd '" + dir + "/vendors/'", &out),
        0)
        << "no /etc/OpenCL/vendors/pocl.icd (Debian's pocl-opencl-icd): " << out;
    ASSERT_EQ(run_command("OCL_ICD_VENDORS='" + dir + "/vendors' POCL_DEVICES='pthread pthread' CLPPM_CACHE_DIR='" +
                              dir + "/cache' " + clppm_binary() +
                              " --device auto --width 16 --height 16 --passes 1 --no-png -o '" + dir + "/a.exr'",
                          &out),
              0)
        << out;
    EXPECT_NE(out.find("--device auto: [0] "), std::string::npos) << out;
    EXPECT_NE(out.find("(pocl), the only device"), std::string::npos) << out;
}
