// KHR_materials_diffuse_transmission end to end (the lobe itself is in bsdf_model_test.cpp against
// a host reference: eval, reciprocity through the surface, sampling below by chi-square, white
// furnace): the loader reads factors and textures; a plate in a uniform white world, which lights
// both of its sides, shows its closed form in every integrator (photons that arrive behind it are
// gathered by hit points in front); a translucent box with a volume absorbs inside alike in every
// integrator.
#include <gtest/gtest.h>

#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

} // namespace

TEST(DiffuseTransmission, LoadsFactorsAndTextures) {
    Scene s = load_gltf(data("dt_textured.gltf"));
    ASSERT_EQ(s.materials.size(), 1u);
    const dev::Material& m = s.materials[0];
    EXPECT_FLOAT_EQ(m.diffuse_transmission, 0.75f);
    EXPECT_FLOAT_EQ(m.diffuse_transmission_color[0], 0.5f);
    EXPECT_FLOAT_EQ(m.diffuse_transmission_color[1], 0.25f);
    EXPECT_FLOAT_EQ(m.diffuse_transmission_color[2], 1.0f);
    EXPECT_GE(m.diffuse_transmission_tex, 0);
    EXPECT_GE(m.diffuse_transmission_color_tex, 0);
    EXPECT_NE(m.diffuse_transmission_tex, m.diffuse_transmission_color_tex) << "colour is sRGB, the factor linear";
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    // Without the extension: none, and a white colour.
    Scene plain = load_gltf(data("coat_plate.gltf"));
    EXPECT_EQ(plain.materials[0].diffuse_transmission, 0.f);
    EXPECT_EQ(plain.materials[0].diffuse_transmission_tex, -1);
}

TEST(DiffuseTransmission, PlateInAWhiteWorldShowsItsClosedForm) {
    // Radiance 1 on both sides: (1 - dt) base + dt colour, and under a smooth layer (F0 0.04,
    // views within 3 degrees of the normal) 0.04 + 0.96 times that.
    const double color[3] = {1.0, 0.5, 0.25};
    struct Case {
        const char* file;
        double dt, base, layer;
    };
    for (const Case& k : {Case{"dt_full_plate.gltf", 1.0, 0.0, 0.0}, Case{"dt_half_plate.gltf", 0.5, 0.2, 0.0},
                          Case{"dt_layer_plate.gltf", 0.5, 0.2, 0.04}})
        for (const char* integrator : {"pt", "bpt", "vcm", "sppm", "pppm", "ppm"}) {
            SCOPED_TRACE(std::string(k.file) + " " + integrator);
            const bool photons = std::string(integrator).find("pm") != std::string::npos;
            std::array<double, 3> m = render_test_scene_channels(k.file, integrator, photons ? 48 : 256, 20000);
            for (int c = 0; c < 3; ++c) {
                const double want = k.layer + (1 - k.layer) * ((1 - k.dt) * k.base + k.dt * color[c]);
                // Density estimation at the plate's edges and the smooth layer's Fresnel
                // over the 3 degrees, and noise: within 1.5% for photons, 0.8% otherwise.
                EXPECT_NEAR(m[size_t(c)], want, (photons ? 0.015 : 0.008) * want) << "channel " << c;
            }
        }
}

TEST(DiffuseTransmission, VolumeAbsorbsAlikeInEveryIntegrator) {
    // A point light behind a translucent box 0.5 thick: light crosses the back face diffusely,
    // the inside (absorbing or clear) and the front face. No closed form (paths inside have every
    // length), but every integrator must agree, and the tint must follow the attenuation colour
    // (0.5, 0.25, 1): blue passes unabsorbed, red and green less than their straight-through
    // exp(-sigma d) since diffuse paths are longer.
    // The clear box itself must agree as well: the photon integrators' disc coverage once took its
    // faces for ended discs (their chords passed the translucent surface) and made it 8 times as
    // bright as pt's, which the ratio hid.
    std::array<double, 3> first{}, first_clear{};
    for (const char* integrator : {"pt", "bpt", "vcm", "sppm", "ppm"}) {
        SCOPED_TRACE(integrator);
        std::array<double, 3> tinted = render_test_scene_channels("dt_box_volume.gltf", integrator, 32, 100000);
        std::array<double, 3> clear = render_test_scene_channels("dt_box_clear.gltf", integrator, 32, 100000);
        for (int c = 0; c < 3; ++c) {
            ASSERT_GT(clear[size_t(c)], 1.0) << "the point light shines through the box";
            const double ratio = tinted[size_t(c)] / clear[size_t(c)];
            if (first[size_t(c)] == 0) first[size_t(c)] = ratio, first_clear[size_t(c)] = clear[size_t(c)];
            EXPECT_NEAR(ratio, first[size_t(c)], 0.02 * first[size_t(c)]) << "channel " << c << " against pt";
            EXPECT_NEAR(clear[size_t(c)], first_clear[size_t(c)], 0.03 * first_clear[size_t(c)])
                << "channel " << c << " of the clear box against pt";
        }
        EXPECT_NEAR(tinted[2] / clear[2], 1.0, 0.01);
        EXPECT_LT(tinted[0] / clear[0], 0.5);
        EXPECT_LT(tinted[1] / clear[1], 0.25);
        EXPECT_GT(tinted[1] / clear[1], 0.02);
    }
}
