// Progressive photon mapping end to end: analytic scenes whose radiance is known, agreement with
// the path tracer on a diffuse scene, determinism, and images free of NaN and Inf.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/device_scene.h"
#include "scene_builders.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

RenderSettings small(unsigned w, unsigned h, uint64_t photons, DirectLighting direct) {
    RenderSettings s;
    s.integrator = "ppm";
    s.spp = 1;
    s.width = w, s.height = h;
    s.photons = photons;
    s.direct = direct;
    return s;
}

} // namespace

TEST(Ppm, FurnaceConvergesToLeOverOneMinusRho) {
    for (DirectLighting direct : {DirectLighting::Photons, DirectLighting::Sample}) {
        Image img = render_passes(furnace(0.5f, 1.0f), small(32, 32, 50000, direct), 16);
        EXPECT_EQ(count_nonfinite(img), 0u);
        double mean = mean_radiance(img);
        EXPECT_NEAR(mean, 2.0, 0.03) << "direct=" << to_string(direct);
    }
}

TEST(Ppm, PlaneUnderPointLightMatchesAnalyticIrradiance) {
    const float rho = 0.5f, I = 10.f, h = 1.f;
    for (DirectLighting direct : {DirectLighting::Photons, DirectLighting::Sample}) {
        Scene scene = plane_under_point_light(rho, I, h);
        RenderSettings s = small(32, 32, 100000, direct);
        float bmin[3] = {-4, 0, -4}, bmax[3] = {4, 0, 4};
        dev::Camera cam = make_camera(scene, s, bmin, bmax, nullptr);
        Image img = render_passes(scene, s, 24);
        EXPECT_LT(plane_error(img, cam, 4, 28, 1, rho, I, h), 0.03) << "direct=" << to_string(direct);
    }
}

// Inside its inner cone a spot light is a point light; a directional light gives rho/pi E cos.
TEST(Ppm, SpotAndDirectionalLightsMatchAnalyticRadiance) {
    const float rho = 0.5f, I = 10.f, h = 1.f;
    for (DirectLighting direct : {DirectLighting::Photons, DirectLighting::Sample}) {
        Scene spot = plane_under_point_light(rho, I, h);
        spot.punctual_lights.clear();
        add_spot_light(spot, {0, h, 0}, I, 1.2f, 1.3f); // the inner cone covers the centre region
        RenderSettings s = small(32, 32, 100000, direct);
        float bmin[3] = {-4, 0, -4}, bmax[3] = {4, 0, 4};
        dev::Camera cam = make_camera(spot, s, bmin, bmax, nullptr);
        Image img = render_passes(spot, s, 16);
        EXPECT_LT(plane_error(img, cam, 8, 24, 0, rho, I, h), 0.04) << "spot, direct=" << to_string(direct);

        Scene sun = plane_under_point_light(rho, I, h);
        sun.punctual_lights.clear();
        const float E = 3.f, c = std::cos(0.5f);
        add_directional_light(sun, {std::sin(0.5f), -c, 0}, E);
        Image lit = render_passes(sun, small(32, 32, 100000, direct), 16);
        EXPECT_NEAR(region_mean(lit, 8, 8, 24, 24) / (rho / M_PI * E * c), 1.0, 0.03)
            << "directional, direct=" << to_string(direct);
    }
}

TEST(Ppm, AgreesWithPathTracerOnDiffuseBox) {
    RenderSettings s = small(32, 32, 100000, DirectLighting::Sample);
    // A radius well below the 32-pixel footprint keeps PPM's boundary bias in the corners small.
    s.radius = 0.04;
    Image ppm = render_passes(diffuse_box(), s, 32);
    s.integrator = "pt";
    Image pt = render_passes(diffuse_box(), s, 512);
    EXPECT_EQ(count_nonfinite(ppm), 0u);
    EXPECT_EQ(count_nonfinite(pt), 0u);
    EXPECT_NEAR(mean_radiance(ppm) / mean_radiance(pt), 1.0, 0.02);
    // Quadrants agree too (colour bleeding on either side, the block's shadow).
    for (int q = 0; q < 4; ++q) {
        int x0 = (q & 1) * 16, y0 = (q >> 1) * 16;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(region_mean(ppm, x0, y0, x0 + 16, y0 + 16, c) / region_mean(pt, x0, y0, x0 + 16, y0 + 16, c),
                        1.0, 0.05)
                << "quadrant " << q << " channel " << c;
    }
}

TEST(Ppm, SameSeedGivesTheSameImageBitForBit) {
    RenderSettings s = small(24, 24, 20000, DirectLighting::Sample);
    Image a = render_passes(diffuse_box(), s, 3), b = render_passes(diffuse_box(), s, 3);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)));
    s.seed = 2;
    Image c = render_passes(diffuse_box(), s, 3);
    EXPECT_NE(0, std::memcmp(a.rgb.data(), c.rgb.data(), a.rgb.size() * sizeof(float)));
}

// Hachisuka et al. 2008, Fig. 7 in miniature: with pure photon estimation, the error against a
// converged path-traced reference falls as passes (and so photons) grow.
TEST(Ppm, ErrorFallsAsPassesGrow) {
    RenderSettings pt = small(24, 24, 0, DirectLighting::Photons);
    pt.integrator = "pt";
    Image ref = render_passes(diffuse_box(), pt, 4096);
    auto rel_rmse = [&](const Image& img) {
        double se = 0, mean = mean_radiance(ref);
        for (size_t i = 0; i < img.rgb.size(); ++i) se += std::pow(double(img.rgb[i]) - ref.rgb[i], 2);
        return std::sqrt(se / double(img.rgb.size())) / mean;
    };
    RenderSettings s = small(24, 24, 20000, DirectLighting::Photons);
    s.radius = 0.05; // below the 24-pixel footprint, so that noise, not blur, dominates early
    std::vector<double> errors;
    for (uint64_t passes : {1, 4, 16, 64}) errors.push_back(rel_rmse(render_passes(diffuse_box(), s, passes)));
    for (size_t i = 1; i < errors.size(); ++i)
        EXPECT_LT(errors[i], errors[i - 1]) << "error did not fall from " << errors[i - 1] << " to " << errors[i];
    EXPECT_LT(errors.back(), 0.5 * errors.front());
    ::testing::Test::RecordProperty("relative_rmse_64_passes", std::to_string(errors.back()));
    std::printf("relative RMSE after 1, 4, 16, 64 passes: %.4f %.4f %.4f %.4f\n", errors[0], errors[1], errors[2],
                errors[3]);
}
