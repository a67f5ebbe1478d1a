// Stochastic and probabilistic PPM: they converge to the same image as PPM where there is no
// distributed effect, glossy surfaces agree with the path tracer, and energy is conserved.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/progressive_update.h"
#include "integrators/sppm_integrator.h"
#include "scene_builders.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// The scene rendered by `integrator` for `passes` passes, with s's other settings.
Image render_with(const Scene& scene, RenderSettings s, const char* integrator, uint64_t passes) {
    s.integrator = integrator;
    return render_passes(scene, s, passes);
}

void expect_images_agree(const Image& a, const Image& b, double mean_tol, double quad_tol, const std::string& what) {
    ASSERT_EQ(count_nonfinite(a), 0u) << what;
    ASSERT_EQ(count_nonfinite(b), 0u) << what;
    EXPECT_NEAR(mean_radiance(a) / mean_radiance(b), 1.0, mean_tol) << what;
    const int h = a.width / 2;
    for (int q = 0; q < 4; ++q) {
        int x0 = (q & 1) * h, y0 = (q >> 1) * h;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(region_mean(a, x0, y0, x0 + h, y0 + h, c) / region_mean(b, x0, y0, x0 + h, y0 + h, c), 1.0,
                        quad_tol)
                << what << ", quadrant " << q << " channel " << c;
    }
}

} // namespace

// Without distributed effects (pixel-centred PPM vs jittered SPPM/PPPM differ only by the pixel
// filter, which averages out in region means) the three photon mappers agree.
TEST(Sppm, ThreeIntegratorsConvergeToTheSameImage) {
    RenderSettings s = square_settings("ppm", 32, 50000);
    s.radius = 0.04;
    const Scene box = diffuse_box();
    const Image ppm = render_with(box, s, "ppm", 48);
    expect_images_agree(render_with(box, s, "sppm", 48), ppm, 0.015, 0.04, "sppm vs ppm");
    expect_images_agree(render_with(box, s, "pppm", 48), ppm, 0.015, 0.04, "pppm vs ppm");
}

TEST(Sppm, GlossyBoxAgreesWithPathTracer) {
    RenderSettings s = square_settings("sppm", 32, 50000);
    s.radius = 0.04;
    expect_images_agree(render_with(glossy_box(), s, "sppm", 64), render_with(glossy_box(), s, "pt", 1024), 0.02, 0.06,
                        "glossy sppm vs pt");
}

// A glossy conductor never reflects more than arrives: the glossy furnace stays below the
// Lambertian furnace of the same F0 (Le / (1 - F0)), and SPPM and PT agree on it.
TEST(Sppm, GlossyFurnaceDoesNotGainEnergy) {
    const RenderSettings s = square_settings("sppm", 16, 50000);
    const Scene furnace = glossy_furnace(0.5f, 0.6f, 1.f);
    const Image sppm = render_with(furnace, s, "sppm", 16), pt = render_with(furnace, s, "pt", 512);
    EXPECT_LT(mean_radiance(sppm), 2.0 * 1.01);
    EXPECT_LT(mean_radiance(pt), 2.0 * 1.01);
    EXPECT_GT(mean_radiance(pt), 1.5); // Schlick raises F above F0 at grazing angles; G loses a little
    EXPECT_NEAR(mean_radiance(sppm) / mean_radiance(pt), 1.0, 0.02);
}

// PPPM's radius sequence, Knaus and Zwicker 2011 Eq. 20, against the closed form
// r_i^2 = r_1^2 prod_{k=1}^{i-1} (k + alpha)/(k + 1).
TEST(Sppm, PppmRadiusSequence) {
    double r2 = 1.0, alpha = 0.7, prod = 1.0;
    for (uint64_t i = 1; i < 1000; ++i) {
        prod *= (double(i) + alpha) / double(i + 1);
        r2 = next_pppm_radius2(r2, i, alpha);
        ASSERT_NEAR(r2, prod, 1e-12 * prod);
    }
    // Asymptotically r_i^2 ~ i^(alpha - 1).
    EXPECT_NEAR(std::log(prod) / std::log(1000.0), alpha - 1.0, 0.05);
}
