// One image on every OpenCL implementation (issue 58): each integrator renders the same scenes
// with the same seed on one CPU device of every platform the loader lists, and each image is
// compared with the first platform's (PoCL's, where both are there). Same seed, same samples: the
// images may differ only where the implementations round differently, which moves a path here and
// there; so the difference, box-filtered 4 x 4 (bias more than noise), must lie far below the
// difference between two seeds on one device, and the means must agree within that noise.
//
// With one implementation there is nothing to compare and the tests skip, saying so.
// scripts/check_implementations.sh installs Intel's CPU runtime from PyPI and runs this binary
// with both (the ctest entry `implementations`); Intel's vectoriser broke the path tracer, VCM and
// BPT there (kernels/portability.h), which these tests caught.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "device/device.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// One CPU device of each platform, in the loader's order (--device takes their index).
std::vector<DeviceInfo> one_cpu_per_platform() {
    std::vector<DeviceInfo> out;
    for (const DeviceInfo& d : list_devices()) {
        if (!(d.type & CL_DEVICE_TYPE_CPU)) continue;
        if (std::none_of(out.begin(), out.end(),
                         [&](const DeviceInfo& o) { return o.platform_name == d.platform_name; }))
            out.push_back(d);
    }
    // PoCL first: the implementation the rest of the suite is proven on is the reference.
    for (size_t i = 1; i < out.size(); ++i)
        if (out[i].implementation() == "pocl") std::swap(out[0], out[i]);
    return out;
}

struct Case {
    const char* what;
    std::string args; // the scene and what it needs
};

std::vector<Case> cases() {
    const std::string scenes = CLPPM_SCENES_DIR;
    return {
        {"the default Cornell box (glass, mirror, area light)", ""},
        {"the caustic scene", "'" + scenes + "/caustic.gltf'"},
        {"the skylit room (sun and sky)", "'" + scenes + "/skylight.gltf'"},
        {"the dispersion box", "'" + scenes + "/dispersion_box.gltf'"},
        {"the Cornell box under the studio environment", "--env studio"},
    };
}

Image render(const DeviceInfo& d, const std::string& integrator, const Case& c, int seed, const std::string& dir) {
    const std::string out =
        dir + "/" + integrator + "_" + std::to_string(d.index) + "_" + std::to_string(seed) + ".exr";
    const std::string args = c.args + " --device " + std::to_string(d.index) + " --integrator " + integrator +
                             " --width 40 --height 40 --passes 8 --photons 20000 --seed " + std::to_string(seed) +
                             " --quiet --no-png -o '" + out + "'";
    std::string log;
    const int rc = run_clppm(args, &log);
    EXPECT_EQ(rc, 0) << d.platform_name << ": clppm " << args << "\n" << log;
    return rc == 0 ? read_exr(out) : Image{};
}

// Relative MSE of the 4 x 4 box-filtered images.
double box4_rel_mse(const Image& a, const Image& b) {
    return compare_images(box_filter(a, 4), box_filter(b, 4)).rel_mse;
}

// The standard error of one image's mean radiance, from the per-pixel differences d of two seeds'
// images: Var(d) = 2 Var(pixel), so sigma_mean = sd(d) / sqrt(2 N).
double mean_standard_error(const Image& a, const Image& b) {
    const size_t n = a.rgb.size() / 3;
    double s = 0, s2 = 0;
    for (size_t i = 0; i < n; ++i) {
        const double d = (double(a.rgb[3 * i]) + a.rgb[3 * i + 1] + a.rgb[3 * i + 2] - b.rgb[3 * i] - b.rgb[3 * i + 1] -
                          b.rgb[3 * i + 2]) /
                         3.0;
        s += d;
        s2 += d * d;
    }
    const double var = (s2 - s * s / double(n)) / double(n - 1);
    return std::sqrt(var / (2.0 * double(n)));
}

bool bit_identical(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.rgb == b.rgb;
}

// Why there are not two implementations to compare ("" when there are). Under
// scripts/check_implementations.sh, which has seen both listed, one alone is also a failure.
std::string why_not_two(const std::vector<DeviceInfo>& devices) {
    if (devices.size() >= 2) return "";
    if (std::getenv("CLPPM_REQUIRE_IMPLEMENTATIONS"))
        ADD_FAILURE() << "CLPPM_REQUIRE_IMPLEMENTATIONS is set but " << devices.size()
                      << " OpenCL implementation lists a CPU";
    return "one OpenCL implementation with a CPU device here: nothing to compare; "
           "scripts/check_implementations.sh adds Intel's CPU runtime";
}

void expect_same_image_everywhere(const std::string& integrator) {
    const std::vector<DeviceInfo> devices = one_cpu_per_platform();
    if (const std::string why = why_not_two(devices); !why.empty()) GTEST_SKIP() << why;
    const std::string dir = make_temp_dir("implementations_" + integrator);
    for (const Case& c : cases()) {
        const DeviceInfo& ref = devices[0];
        const Image a = render(ref, integrator, c, 1, dir);
        const Image a2 = render(ref, integrator, c, 2, dir);
        if (a.rgb.empty() || a2.rgb.empty()) continue;
        const double noise_box = box4_rel_mse(a2, a);
        const double sigma_mean = mean_standard_error(a2, a);
        ASSERT_GT(noise_box, 0.0) << "two seeds gave the same image: the comparison could not fail";
        for (size_t i = 1; i < devices.size(); ++i) {
            const Image b = render(devices[i], integrator, c, 1, dir);
            if (b.rgb.empty()) continue;
            const ImageDifference d = compare_images(b, a);
            const double box = box4_rel_mse(b, a);
            std::printf("%s, %s: %s against %s: %s; box-4 relative MSE %.3g (two seeds: %.3g), mean ratio %.9f (its "
                        "standard error %.2g)\n",
                        integrator.c_str(), c.what, devices[i].platform_name.c_str(), ref.platform_name.c_str(),
                        bit_identical(a, b) ? "bit-identical" : "not bit-identical", box, noise_box,
                        d.mean_a / d.mean_b, sigma_mean / d.mean_b);
            EXPECT_EQ(d.nonfinite_a, 0u) << devices[i].platform_name << ", " << c.what;
            EXPECT_LT(box, 1e-3 * noise_box)
                << integrator << ", " << c.what << ": " << devices[i].platform_name << " against " << ref.platform_name;
            // Same samples: the means differ by far less than one seed's noise.
            EXPECT_LE(std::fabs(d.mean_a - d.mean_b), 0.05 * sigma_mean)
                << integrator << ", " << c.what << ": " << devices[i].platform_name << " mean " << d.mean_a << ", "
                << ref.platform_name << " " << d.mean_b << " (the mean's standard error: " << sigma_mean << ")";
        }
    }
}

} // namespace

// --device auto renders a moment on each implementation and picks one (render/device_auto.h): it
// says both rates, keeps the choice in the cache, takes it from there the next time, and the
// image is the chosen device's bit for bit.
TEST(Implementations, AutoMeasuresEachAndRemembers) {
    const std::vector<DeviceInfo> devices = one_cpu_per_platform();
    if (const std::string why = why_not_two(devices); !why.empty()) GTEST_SKIP() << why;
    const std::string dir = make_temp_dir("implementations_auto"), cache = "CLPPM_CACHE_DIR='" + dir + "/cache' ";
    const std::string args = " --integrator pt --width 32 --height 32 --passes 4 --seed 3 --no-png -o '" + dir;
    std::string first, second, out;
    ASSERT_EQ(run_command(cache + clppm_binary() + " --device auto" + args + "/auto.exr'", &first), 0) << first;
    const size_t at = first.find("--device auto: rendering on [");
    ASSERT_NE(at, std::string::npos) << first;
    EXPECT_NE(first.find("passes/s there, "), std::string::npos) << first;
    for (const DeviceInfo& d : devices) EXPECT_NE(first.find(d.implementation()), std::string::npos) << first;
    const int chosen = std::atoi(first.c_str() + at + std::string("--device auto: rendering on [").size());
    ASSERT_EQ(run_command(cache + clppm_binary() + " --device auto" + args + "/again.exr'", &second), 0) << second;
    EXPECT_NE(second.find("--device auto: [" + std::to_string(chosen) + "] "), std::string::npos) << second;
    EXPECT_NE(second.find("measured the fastest before"), std::string::npos) << second;
    ASSERT_EQ(run_command(clppm_binary() + " --device " + std::to_string(chosen) + args + "/named.exr'", &out), 0)
        << out;
    const Image a = read_exr(dir + "/auto.exr"), b = read_exr(dir + "/again.exr"), c = read_exr(dir + "/named.exr");
    ASSERT_FALSE(a.rgb.empty());
    EXPECT_TRUE(bit_identical(a, c)) << "the image is not the chosen device's";
    EXPECT_TRUE(bit_identical(b, c)) << "the remembered choice rendered another image";
}

TEST(Implementations, Ppm) { expect_same_image_everywhere("ppm"); }
TEST(Implementations, Sppm) { expect_same_image_everywhere("sppm"); }
TEST(Implementations, Pppm) { expect_same_image_everywhere("pppm"); }
TEST(Implementations, PathTracer) { expect_same_image_everywhere("pt"); }
TEST(Implementations, Vcm) { expect_same_image_everywhere("vcm"); }
TEST(Implementations, Bpt) { expect_same_image_everywhere("bpt"); }

// The path tracer in the world's medium (tests/data/fog_room.gltf: chromatic fog, a glass cube
// holding its own volume, an area and a point light). A free flight's length is a logarithm of
// the path's number, which the implementations round differently in the last bit; the point moves
// that much, and a path whose next choice sits on the edge (scatter or reach the wall) takes the
// other branch. So the same seed gives images that differ more than on surfaces alone, still far
// below the noise between two seeds: bounds of 3% of that noise and a quarter of the mean's standard
// error.
TEST(Implementations, PathTracerInFog) {
    const std::vector<DeviceInfo> devices = one_cpu_per_platform();
    if (const std::string why = why_not_two(devices); !why.empty()) GTEST_SKIP() << why;
    const std::string dir = make_temp_dir("implementations_fog");
    const Case fog{"the fog room", "'" + std::string(CLPPM_TEST_DATA) + "/fog_room.gltf'"};
    const Image a = render(devices[0], "pt", fog, 1, dir), a2 = render(devices[0], "pt", fog, 2, dir);
    ASSERT_FALSE(a.rgb.empty() || a2.rgb.empty());
    const double noise_box = box4_rel_mse(a2, a), sigma_mean = mean_standard_error(a2, a);
    ASSERT_GT(noise_box, 0.0);
    for (size_t i = 1; i < devices.size(); ++i) {
        const Image b = render(devices[i], "pt", fog, 1, dir);
        ASSERT_FALSE(b.rgb.empty());
        const ImageDifference d = compare_images(b, a);
        const double box = box4_rel_mse(b, a);
        std::printf("pt, %s: %s against %s: box-4 relative MSE %.3g (two seeds: %.3g), mean ratio %.9f (its standard "
                    "error %.2g)\n",
                    fog.what, devices[i].platform_name.c_str(), devices[0].platform_name.c_str(), box, noise_box,
                    d.mean_a / d.mean_b, sigma_mean / d.mean_b);
        EXPECT_EQ(d.nonfinite_a, 0u);
        EXPECT_LT(box, 0.03 * noise_box) << devices[i].platform_name;
        EXPECT_LE(std::fabs(d.mean_a - d.mean_b), 0.25 * sigma_mean) << devices[i].platform_name;
    }
}
