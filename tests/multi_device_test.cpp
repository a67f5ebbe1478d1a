// Several devices at once: PoCL is made to expose two CPU devices (POCL_DEVICES), the photons (or,
// for vcm, the pixels) of each pass are shared between them, and the image is the same bit for bit
// as on one device.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

const std::string kTwo = "POCL_DEVICES='pthread pthread' ";

int run_two(const std::string& args, std::string* out) { return run_command(kTwo + clppm_binary() + " " + args, out); }

} // namespace

TEST(MultiDevice, TwoDevicesGiveTheSameImageAsOne) {
    std::string out;
    ASSERT_EQ(run_two("--list-devices", &out), 0) << out;
    ASSERT_NE(out.find("[1] "), std::string::npos) << "PoCL did not expose two devices:\n" << out;
    for (const char* integrator : {"ppm", "sppm", "pppm", "vcm"}) {
        std::string d = make_temp_dir("multi");
        const std::string args = std::string(" --width 32 --height 32 --passes 4 --photons 20000 --no-png --quiet") +
                                 " --integrator " + integrator;
        ASSERT_EQ(run_two(args + " --device 0 -o " + d + "/one.exr", &out), 0) << out;
        ASSERT_EQ(run_two(args + " --device 0 --device 1 -o " + d + "/two.exr --stats-json " + d + "/s.json", &out), 0)
            << out;
        ASSERT_EQ(run_two(args + " --device all -o " + d + "/all.exr", &out), 0) << out;
        Image one = read_exr(d + "/one.exr"), two = read_exr(d + "/two.exr"), all = read_exr(d + "/all.exr");
        EXPECT_EQ(one.rgb, two.rgb) << integrator;
        EXPECT_EQ(one.rgb, all.rgb) << integrator;
        // Both devices did work in the last pass.
        std::string js = slurp(d + "/s.json");
        size_t at = js.find("\"device_photons_last_pass\": [");
        ASSERT_NE(at, std::string::npos) << js;
        std::istringstream list(js.substr(at + 29));
        unsigned long a = 0, b = 0;
        char comma = 0;
        list >> a >> comma >> b;
        EXPECT_GT(a, 0u) << js;
        EXPECT_GT(b, 0u) << js;
        // Photons, or for vcm the camera sub-paths' pixels (each device traces all light sub-paths).
        EXPECT_EQ(a + b, std::string(integrator) == "vcm" ? 1024u : 20000u) << js;
    }
}

TEST(MultiDevice, ADeviceNamedTwiceIsAnError) {
    std::string out;
    EXPECT_EQ(run_two("--device 0 --device 0 -o " + make_temp_dir("out") + "/x.exr", &out), 1);
    EXPECT_NE(out.find("--device 0: device [0]"), std::string::npos) << out;
    EXPECT_NE(out.find("given twice"), std::string::npos) << out;
    EXPECT_EQ(run_two("--device 0 --device 7 -o " + make_temp_dir("out") + "/x.exr", &out), 1);
    EXPECT_NE(out.find("--device 7: no device with index 7"), std::string::npos) << out;
}
