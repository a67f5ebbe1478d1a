// KHR_materials_clearcoat end to end (the lobe itself is in bsdf_model_test.cpp against a host
// reference: eval, reciprocity, chi-square, weights and white furnaces): the loader reads the
// factors, textures and the coat's own normal map; a black plate under a full coat in a uniform
// white world shows the coat's directional albedo, exactly Schlick's 0.04 when the coat is smooth
// (a delta lobe, so every integrator gets it without noise) and the GGX layer's albedo E(1) from
// kernels/ggx_albedo.h when it is rough (0.5), within the noise of a few passes.
#include <gtest/gtest.h>

#include <cmath>

#include "ggx_albedo.h"
#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

} // namespace

TEST(Clearcoat, LoadsFactorsTexturesAndItsNormalMap) {
    Scene s = load_gltf(data("coat_textured.gltf"));
    ASSERT_EQ(s.materials.size(), 1u);
    const dev::Material& m = s.materials[0];
    EXPECT_FLOAT_EQ(m.clearcoat, 0.8f);
    EXPECT_FLOAT_EQ(m.clearcoat_roughness, 0.3f);
    EXPECT_GE(m.clearcoat_tex, 0);
    EXPECT_GE(m.clearcoat_roughness_tex, 0);
    EXPECT_GE(m.clearcoat_normal_tex, 0);
    EXPECT_FLOAT_EQ(m.clearcoat_normal_scale, 0.5f);
    EXPECT_FALSE(s.tangents.empty()) << "the coat's normal map needs tangents";
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    Scene plain = load_gltf(data("coat_plate.gltf"));
    EXPECT_EQ(plain.materials[0].clearcoat_tex, -1);
    EXPECT_EQ(plain.materials[0].clearcoat_normal_tex, -1);
}

TEST(Clearcoat, SmoothCoatShowsSchlicksF0InEveryIntegrator) {
    for (const char* integrator : {"pt", "sppm", "ppm", "vcm", "bpt"}) {
        SCOPED_TRACE(integrator);
        // Views within 3 degrees of the normal: (1 - cos)^5 below 1e-12.
        EXPECT_NEAR(render_test_scene_mean("coat_plate.gltf", integrator, 2, 200000), 0.04, 1e-5);
    }
}

TEST(Clearcoat, RoughCoatShowsTheLayersAlbedo) {
    // E(mu = 1) at roughness 0.5 (alpha 0.25), the table's last column at row 0.5 (GGX_ALBEDO_ALPHA
    // rows over roughness 0..1): 0.04 A + 0.96 B.
    const double y = 0.5 * (GGX_ALBEDO_ALPHA - 1);
    const int j = int(y);
    const double fy = y - j;
    auto at = [&](const float* t, int row) { return double(t[row * GGX_ALBEDO_MU + GGX_ALBEDO_MU - 1]); };
    auto lerp = [&](const float* t) { return (1 - fy) * at(t, j) + fy * at(t, j + 1); };
    const double want = 0.04 * lerp(ggx_albedo_a) + 0.96 * lerp(ggx_albedo_b);
    ASSERT_GT(want, 0.03);
    ASSERT_LT(want, 0.05);
    for (const char* integrator : {"pt", "sppm"}) {
        SCOPED_TRACE(integrator);
        EXPECT_NEAR(render_test_scene_mean("coat_rough_plate.gltf", integrator, 256, 200000), want, 0.02 * want);
    }
}
