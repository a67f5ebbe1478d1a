// The built-in studio environment (--env studio): its map holds irradiance pi for an upward
// surface (checked by integrating the map independently, by Monte Carlo over directions), its
// brightest texel lies towards the key light, it is finite and positive everywhere, and a white
// floor under it renders as under the uniform white world.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "io/image_io.h"
#include "scene/environment.h"
#include "scene/studio_environment.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// The map's nearest texel towards unit direction d (mean over RGB).
double lookup(const Image& img, double x, double y, double z) {
    const std::array<double, 2> uv = env_uv({x, y, z});
    const int i = std::min(img.width - 1, int(uv[0] * img.width)),
              j = std::min(img.height - 1, int(uv[1] * img.height));
    const size_t k = (size_t(j) * size_t(img.width) + size_t(i)) * 3;
    return (double(img.rgb[k]) + img.rgb[k + 1] + img.rgb[k + 2]) / 3;
}

} // namespace

TEST(StudioEnvironment, AnUpwardSurfaceReceivesPi) {
    const Image img = studio_environment();
    ASSERT_EQ(img.width, 256);
    ASSERT_EQ(img.height, 128);
    for (float v : img.rgb) ASSERT_TRUE(std::isfinite(v) && v > 0.f);
    // E = int L cos dw over the upper hemisphere, by cosine-weighted directions: E = pi mean(L).
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    const int n = 400000;
    double sum = 0;
    for (int k = 0; k < n; ++k) {
        const double r = std::sqrt(u(rng)), phi = 2 * M_PI * u(rng);
        sum += lookup(img, r * std::cos(phi), std::sqrt(std::max(0.0, 1 - r * r)), r * std::sin(phi));
    }
    EXPECT_NEAR(sum / n, 1.0, 0.01); // E / pi
}

TEST(StudioEnvironment, TheBrightestTexelIsTowardsTheKeyLight) {
    const Image img = studio_environment();
    size_t best = 0;
    for (size_t k = 0; k < img.rgb.size(); k += 3)
        if (img.rgb[k + 1] > img.rgb[best + 1]) best = k;
    const size_t texel = best / 3;
    const std::array<double, 3> d = env_direction((double(texel % size_t(img.width)) + 0.5) / img.width,
                                                  (double(texel / size_t(img.width)) + 0.5) / img.height);
    // The key: upper front left, as a camera on +Z looking down -Z sees it.
    const double key[3] = {-0.48, 0.70, 0.53}, n = std::sqrt(0.48 * 0.48 + 0.7 * 0.7 + 0.53 * 0.53);
    EXPECT_GT((d[0] * key[0] + d[1] * key[1] + d[2] * key[2]) / n, std::cos(5 * M_PI / 180));
    EXPECT_GT(d[1], 0.5);
    EXPECT_LT(d[0], 0.0);
    // The ground is darker than the sky straight up.
    EXPECT_LT(lookup(img, 0, -1, 0), 0.5 * lookup(img, 0, 1, 0));
}

TEST(StudioEnvironment, AWhiteFloorLooksAsUnderTheWhiteWorld) {
    const std::string d = make_temp_dir("studio");
    std::string out;
    const std::string floor = std::string(CLPPM_TEST_DATA) + "/env_floor.gltf";
    auto mean = [&](const std::string& args) {
        EXPECT_EQ(run_clppm(floor + " --width 32 --height 32 --integrator pt --passes 64 --env-hidden --no-png " +
                                args + " -o " + d + "/x.exr",
                            &out),
                  0)
            << out;
        const Image img = read_exr(d + "/x.exr");
        double sum = 0;
        for (float v : img.rgb) sum += v;
        return sum / double(img.rgb.size());
    };
    const double white = mean("--env-color 1,1,1"), studio = mean("--env studio");
    EXPECT_NE(out.find("world: --env studio: the built-in studio environment"), std::string::npos) << out;
    EXPECT_NEAR(studio / white, 1.0, 0.02);
    // A file named studio is ./studio.
    EXPECT_EQ(run_clppm(floor + " --env ./studio -o " + d + "/y.exr", &out), 1);
    EXPECT_NE(out.find("--env ./studio"), std::string::npos) << out;
}
