// KHR_materials_volume and transmissionTexture. Inside a mesh of an absorbing material light
// falls off by Beer-Lambert's law: an emitter seen through a glass slab 0.5 thick of
// attenuationColor (0.5, 0.25, 1) at attenuationDistance 0.5 is that colour times the clear
// slab's image, channel by channel (the near-normal rays cross the slab once, up to internal
// reflections of F^2 = 0.0016), for photon mapping and the path tracer. A transmissionTexture
// scales transmissionFactor. The same slab at roughness 0.5 under a point light behind it tints
// alike in every integrator: the path tracer's light samples from the far face and the
// bidirectional connections between the two faces run through the volume and are absorbed on
// the way.
#include <gtest/gtest.h>

#include <cmath>

#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "scene_builders.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

// Channel means at 16x16 with the default 200000 photons per pass.
std::array<double, 3> channel_means(const std::string& file, const char* integrator, int passes = 4) {
    return render_test_scene_channels(file, integrator, passes, 200000);
}

} // namespace

TEST(Volume, AttenuationCoefficientsAreMinusLogColourOverDistance) {
    Scene s = load_gltf(data("volume_slab.gltf"));
    const dev::Material& glass = s.materials[0];
    EXPECT_NEAR(glass.attenuation[0], std::log(2.0) / 0.5, 1e-6);
    EXPECT_NEAR(glass.attenuation[1], std::log(4.0) / 0.5, 1e-6);
    EXPECT_EQ(glass.attenuation[2], 0.f);
    EXPECT_EQ(load_gltf(data("volume_clear.gltf")).materials[0].attenuation[0], 0.f);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    Scene t = load_gltf(data("transmission_texture.gltf"));
    ASSERT_GE(t.materials[0].transmission_tex, 0);
    EXPECT_FLOAT_EQ(t.texels[0][0], 0.2f) << "transmissionTexture is linear (51 / 255)";
}

TEST(Volume, BeerLambertThroughASlab) {
    const double T[3] = {0.5, 0.25, 1.0}; // exp(-sigma d) per channel
    for (const char* integrator : {"sppm", "pt"}) {
        SCOPED_TRACE(integrator);
        std::array<double, 3> tinted = channel_means("volume_slab.gltf", integrator);
        std::array<double, 3> clear = channel_means("volume_clear.gltf", integrator);
        for (int c = 0; c < 3; ++c) {
            ASSERT_GT(clear[size_t(c)], 0.8) << "the clear slab passes (1 - F)^2 of the light";
            // Internal reflections scale the ratio by (1 - F^2) / (1 - F^2 T^2), within 0.2%.
            EXPECT_NEAR(tinted[size_t(c)] / clear[size_t(c)], T[c], 0.005 * T[c]) << "channel " << c;
        }
    }
}

TEST(Volume, TransmissionTextureScalesTheFactor) {
    expect_scenes_render_alike("transmission_texture.gltf", "transmission_factor.gltf", 1e-3);
}

TEST(Volume, RoughSlabAbsorbsAlikeInEveryIntegrator) {
    // Rays bend in the rough faces, so paths in the slab are a little longer than its thickness:
    // the ratio sits a little under exp(-sigma d), by the same amount in every integrator.
    const double T[3] = {0.5, 0.25, 1.0};
    std::array<double, 3> first{};
    for (const char* integrator : {"pt", "bpt", "vcm", "sppm"}) {
        SCOPED_TRACE(integrator);
        std::array<double, 3> tinted = channel_means("rough_volume_slab.gltf", integrator, 16);
        std::array<double, 3> clear = channel_means("rough_volume_clear.gltf", integrator, 16);
        for (int c = 0; c < 3; ++c) {
            ASSERT_GT(clear[size_t(c)], 1.0) << "the point light shines through the slab";
            const double ratio = tinted[size_t(c)] / clear[size_t(c)];
            EXPECT_NEAR(ratio, T[c] * 0.99, 0.015 * T[c]) << "channel " << c;
            if (first[size_t(c)] == 0) first[size_t(c)] = ratio;
            EXPECT_NEAR(ratio, first[size_t(c)], 0.005 * T[c]) << "channel " << c << " against the path tracer";
        }
    }
}

// A camera inside a solid of smooth glass (index 1.5) looking out through a face, at normal
// incidence, at an emitter of radiance 1: radiance inside a medium of index n is n^2 times what it
// is outside (L / n^2 is invariant along a ray, Veach 1997, Sec. 5.2), so it sees
// (1 - F) 1.5^2 (1 + F^2 + ...) = 2.1635 with F = 0.04, in every integrator whose camera paths
// refract (an underwater camera). With one BSDF for radiance and importance it saw 0.96, and
// SPPM's and PPM's eye pass, which splits at smooth glass by its own branches, did until it took
// the same scale.
TEST(Volume, ACameraInsideGlassSeesRadianceCompressedByTheIndexSquared) {
    Scene s;
    s.source = "<camera in glass>";
    const uint32_t glass = add_material(s, 1, 1, 1, 0.f, false, MAT_GLASS, 1.5f, 0.f);
    const uint32_t lamp = add_material(s, 0, 0, 0, 1.f);
    const float h = 1;
    // The cube's six faces, wound outwards.
    add_quad(s, {-h, -h, -h}, {-h, h, -h}, {h, h, -h}, {h, -h, -h}, glass); // z = -1, normal -z
    add_quad(s, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}, glass);     // z = +1, normal +z
    add_quad(s, {-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h}, glass); // y = -1, normal -y
    add_quad(s, {-h, h, -h}, {-h, h, h}, {h, h, h}, {h, h, -h}, glass);     // y = +1, normal +y
    add_quad(s, {-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h}, glass); // x = -1, normal -x
    add_quad(s, {h, -h, -h}, {h, h, -h}, {h, h, h}, {h, -h, h}, glass);     // x = +1, normal +x
    add_quad(s, {-3, -3, -3}, {3, -3, -3}, {3, 3, -3}, {-3, 3, -3}, lamp);  // z = -3, facing +z
    add_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 0.2f);
    const double expected = (1 - 0.04) * 2.25 * (1 + 0.04 * 0.04);
    for (const char* integrator : {"pt", "bpt", "vcm", "sppm", "ppm"}) {
        RenderSettings rs;
        rs.width = rs.height = 8;
        rs.integrator = integrator;
        rs.photons = 20000;
        const Image img = render_passes(s, rs, 64);
        EXPECT_NEAR(mean_radiance(img) / expected, 1.0, 0.01) << integrator;
    }
}
