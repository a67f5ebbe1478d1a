// Material textures end to end: a metallicRoughnessTexture is read linear (not as sRGB), its G
// channel scales roughness and its B channel metallic (glTF 2.0, 3.9.2), for photon mapping and
// the path tracer alike. A plane lit by a point light renders the same with a uniform texture as
// with the texture's values written as factors, and clearly differently from the factors the
// texture would leave if it were ignored (the bug this guards: textured assets came out as rough
// metal).
#include <gtest/gtest.h>

#include <cmath>

#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

double render_mean(const std::string& file, const std::string& integrator) {
    return render_test_scene_mean(file, integrator);
}

} // namespace

TEST(MaterialTextures, MetallicRoughnessTexelsAreLinear) {
    Scene s = load_gltf(data("mr_texture.gltf"));
    ASSERT_EQ(s.materials.size(), 1u);
    const dev::Material& m = s.materials[0];
    EXPECT_EQ(m.base_color_tex, -1);
    ASSERT_EQ(m.metallic_roughness_tex, 0);
    ASSERT_EQ(s.texels.size(), 4u);
    for (const auto& t : s.texels) {
        EXPECT_FLOAT_EQ(t[1], 128 / 255.f); // linear: sRGB decoding would give 0.2158
        EXPECT_FLOAT_EQ(t[2], 1.f);
    }
    EXPECT_TRUE(s.warnings.empty()) << ::testing::PrintToString(s.warnings);
}

TEST(MaterialTextures, MetallicRoughnessTextureScalesTheFactors) {
    for (const char* integrator : {"sppm", "pt"}) {
        SCOPED_TRACE(integrator);
        const double textured = render_mean("mr_texture.gltf", integrator);
        const double factors = render_mean("mr_factors.gltf", integrator);
        const double ignored = render_mean("mr_untextured.gltf", integrator);
        ASSERT_GT(factors, 0);
        // Same seed, same material to a rounding of the bilinear weights: a rare path may go
        // another way, nothing more (measured: 2e-7 relative for SPPM).
        EXPECT_NEAR(textured / factors, 1.0, 1e-3);
        // Roughness 1 instead of 0.5 halves this plate's highlight: ignoring the texture shows.
        EXPECT_GT(std::fabs(ignored / factors - 1.0), 0.2);
    }
}

// TEXCOORD_1 through a KHR_texture_transform renders as the transformed coordinates written into
// TEXCOORD_0 (make_surface interpolates the second set, texture_rgba picks and transforms it).
TEST(MaterialTextures, SecondCoordinateSetThroughATransform) {
    expect_scenes_render_alike("uv1_plate_set1.gltf", "uv1_plate_set0.gltf", 1e-3);
}

// KHR_materials_specular's textures scale its factors: specularTexture's alpha the
// specularFactor, specularColorTexture (sRGB) the specularColorFactor.
TEST(MaterialTextures, SpecularTexturesScaleTheFactors) {
    expect_scenes_render_alike("specular_texture.gltf", "specular_factor.gltf", 1e-3);
    for (const char* integrator : {"sppm", "pt"}) // and ignoring them (factors 1) would show
        EXPECT_GT(std::fabs(render_test_scene_mean("specular_untextured.gltf", integrator) /
                                render_test_scene_mean("specular_texture.gltf", integrator) -
                            1.0),
                  0.05);
}
