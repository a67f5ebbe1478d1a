// KHR_materials_sheen end to end (the lobe itself is in bsdf_model_test.cpp against a host
// reference, with its albedo table against an independent quadrature): the loader reads the
// factors and textures, and a black plate under a white sheen of roughness 1 in a uniform white
// world shows the sheen's directional albedo at normal view from kernels/sheen_albedo.h, in the
// path tracer and in SPPM (where the sheen is gathered at the hit points).
#include <gtest/gtest.h>

#include "scene/gltf/gltf_load.h"
#include "sheen_albedo.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

} // namespace

TEST(Sheen, LoadsFactorsAndTextures) {
    Scene s = load_gltf(data("sheen_textured.gltf"));
    ASSERT_EQ(s.materials.size(), 1u);
    const dev::Material& m = s.materials[0];
    EXPECT_FLOAT_EQ(m.sheen_color[0], 0.5f);
    EXPECT_FLOAT_EQ(m.sheen_color[1], 0.25f);
    EXPECT_FLOAT_EQ(m.sheen_color[2], 1.0f);
    EXPECT_FLOAT_EQ(m.sheen_roughness, 0.6f);
    EXPECT_GE(m.sheen_color_tex, 0);
    EXPECT_GE(m.sheen_roughness_tex, 0);
    EXPECT_NE(m.sheen_color_tex, m.sheen_roughness_tex) << "colour is sRGB, roughness linear";
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(Sheen, BlackPlateShowsTheSheensAlbedo) {
    // Views within 3 degrees of the normal, at roughness 1 (the last row): E(1), extrapolated
    // linearly from the last two columns (cos_o 0.953 and 0.984; E falls towards the normal).
    const float* row = sheen_albedo + (SHEEN_ALBEDO_R - 1) * SHEEN_ALBEDO_MU;
    const double want = row[SHEEN_ALBEDO_MU - 1] + 0.5 * (row[SHEEN_ALBEDO_MU - 1] - row[SHEEN_ALBEDO_MU - 2]);
    ASSERT_GT(want, 0.1);
    for (const char* integrator : {"pt", "sppm"}) {
        SCOPED_TRACE(integrator);
        EXPECT_NEAR(render_test_scene_mean("sheen_plate.gltf", integrator, 256, 200000), want, 0.02 * want);
    }
}
