// glTF alphaMode (kernels/alpha.cl). MASK: a card cut out by its texture's alpha renders, in the
// image and in the shadow it casts (closest-hit and any-hit queries alike), as the uncut half of
// the card; BLEND: a half-transparent card that no light path crosses twice renders as the mean
// of the opaque card and no card. For photon mapping and the path tracer.
#include <gtest/gtest.h>

#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "test_util.h"
#include "util/error.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const std::string& name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

double render_mean(const std::string& file, const char* integrator) {
    return render_test_scene_mean(file, integrator, 8, 60000);
}

} // namespace

TEST(AlphaMode, ModesAndCutoffsAreRead) {
    Scene card = load_gltf(data("alpha_mask_card.gltf"));
    EXPECT_EQ(card.materials[1].alpha_mode, ALPHA_MASK);
    EXPECT_FLOAT_EQ(card.materials[1].alpha_cutoff, 0.5f);
    EXPECT_EQ(card.materials[0].alpha_mode, ALPHA_OPAQUE);
    Scene blend = load_gltf(data("alpha_blend_blend.gltf"));
    EXPECT_EQ(blend.materials[1].alpha_mode, ALPHA_BLEND);
    EXPECT_FLOAT_EQ(blend.materials[1].base_color[3], 0.5f);
}

TEST(AlphaMode, MaskedCardRendersAsItsOpaquePart) {
    // The same rays meet the same surfaces: measured identical images.
    expect_scenes_render_alike("alpha_mask_card.gltf", "alpha_mask_half.gltf", 1e-3, 8, 60000);
}

TEST(AlphaMode, BlendedCardIsTheMeanOfOpaqueAndAbsent) {
    for (const char* integrator : {"sppm", "pt"}) {
        SCOPED_TRACE(integrator);
        const double blend = render_mean("alpha_blend_blend.gltf", integrator);
        const double opaque = render_mean("alpha_blend_opaque.gltf", integrator);
        const double none = render_mean("alpha_blend_none.gltf", integrator);
        ASSERT_GT(opaque, 0);
        EXPECT_GT(none / opaque, 1.5) << "the card hides much of the floor";
        // Measured 1.0001 (SPPM) and 0.997 (PT): noise of the stochastic coverage.
        EXPECT_NEAR(blend / (0.5 * (opaque + none)), 1.0, 0.025);
    }
}
