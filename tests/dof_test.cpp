// The thin-lens camera: the plane of focus stays sharp, and an edge off it is blurred by the
// circle of confusion the thin-lens model predicts, to within a pixel.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_builders.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// Two emissive half-planes facing the camera: one at the focus distance (upper half of the
// image), one farther away (lower half), each with a vertical edge on the optical axis.
Scene two_edges(float near_z, float far_z) {
    Scene s;
    s.source = "<two edges>";
    uint32_t e = add_material(s, 0, 0, 0, 1.f);
    add_quad(s, {0, 0, -near_z}, {30, 0, -near_z}, {30, 30, -near_z}, {0, 30, -near_z}, e);
    add_quad(s, {0, -60, -far_z}, {60, -60, -far_z}, {60, 0, -far_z}, {0, 0, -far_z}, e);
    add_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 0.8f);
    return s;
}

// Sum over a row of |profile - ideal step at the centre| (radiance 1 beyond the edge), averaged
// over rows [y0, y1). For a uniform disc blur of radius r this is 4 r / (3 pi) pixels.
double edge_spread(const Image& img, int y0, int y1) {
    double total = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < img.width; ++x) {
            double v = img.rgb[3 * (size_t(y) * img.width + x)];
            total += std::fabs(v - (x >= img.width / 2 ? 1.0 : 0.0));
        }
    return total / (y1 - y0);
}

} // namespace

TEST(DepthOfField, FocalPlaneSharpDefocusMatchesCircleOfConfusion) {
    const int size = 64;
    const double f = 2.0, far = 4.0, aperture = 0.2, yfov = 0.8;
    RenderSettings s;
    s.integrator = "sppm";
    s.width = s.height = size;
    s.photons = 1000;
    s.aperture = aperture;
    s.focus_distance = f;
    Image img = render_passes(two_edges(float(f), float(far)), s, 256);
    ASSERT_EQ(count_nonfinite(img), 0u);

    // Thin lens: a point at depth d spreads over a disc of radius a |d - f| / d on the plane of
    // focus, where one pixel spans 2 f tan(yfov/2) / height.
    const double pixel = 2 * f * std::tan(yfov / 2) / size;
    const double coc_px = aperture * std::fabs(far - f) / far / pixel;
    const double sharp = edge_spread(img, 4, 24);    // upper half: in focus
    const double blurred = edge_spread(img, 40, 60); // lower half: beyond focus
    // The box pixel filter alone spreads an edge by 1/4 pixel when it falls inside a pixel; here
    // the edge lies on a pixel boundary, so an in-focus edge has (almost) no spread.
    std::printf("edge spread in focus %.3f px; blur radius %.3f px, thin lens %.3f px\n", sharp, blurred * 3 * M_PI / 4,
                coc_px);
    EXPECT_LT(sharp, 0.25) << "the plane of focus is not sharp";
    const double radius = blurred * 3 * M_PI / 4;
    EXPECT_NEAR(radius, coc_px, 1.0) << "measured blur radius " << radius << " px, thin lens predicts " << coc_px;

    // And a pinhole camera renders both edges sharp.
    s.aperture = 0;
    Image pinhole = render_passes(two_edges(float(f), float(far)), s, 16);
    EXPECT_LT(edge_spread(pinhole, 40, 60), 0.25);
}
