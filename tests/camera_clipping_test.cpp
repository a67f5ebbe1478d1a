// glTF cameras as viewers show them: orthographic cameras (parallel rays over 2 xmag x 2 ymag, the
// same image from any distance) and the near plane znear (nothing nearer is seen, in the camera's
// rays and in the light tracing that bidirectional methods splat through the lens).
// tests/data/ortho_square*.gltf and znear_*.gltf (tests/data/make_test_gltf.py).
#include <gtest/gtest.h>

#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

Image render(const char* file, const char* integrator, int passes = 2) {
    std::string d = make_temp_dir("camera"), out;
    const std::string args = data(file) + " --width 32 --height 32 --passes " + std::to_string(passes) +
                             " --quiet --no-png --integrator " + integrator + " -o " + d + "/i.exr";
    EXPECT_EQ(run_clppm(args, &out), 0) << out;
    return read_exr(d + "/i.exr");
}

float px(const Image& img, int x, int y, int c) { return img.rgb[size_t(3 * (y * img.width + x) + c)]; }

} // namespace

TEST(CameraClipping, OrthographicSeesTheSameSizeAtAnyDistance) {
    // xmag = ymag = 1 over 32 pixels: the unit square covers pixels 8..23 in both directions.
    const float square[3] = {0.2f, 0.5f, 0.8f};
    for (const char* integrator : {"pt", "sppm"}) {
        SCOPED_TRACE(integrator);
        Image near = render("ortho_square.gltf", integrator), far = render("ortho_square_far.gltf", integrator);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const bool inside = x >= 8 && x < 24 && y >= 8 && y < 24;
                for (int c = 0; c < 3; ++c) {
                    ASSERT_NEAR(px(near, x, y, c), inside ? square[c] : 1.f, 1e-5f) << x << "," << y;
                    ASSERT_EQ(px(near, x, y, c), px(far, x, y, c)) << x << "," << y;
                }
            }
    }
}

TEST(CameraClipping, BidirectionalMethodsRefuseAnOrthographicCamera) {
    std::string out;
    EXPECT_NE(run_clppm(data("ortho_square.gltf") + " --width 8 --height 8 --passes 1 --integrator vcm -o " +
                            make_temp_dir("camera") + "/i.exr",
                        &out),
              0);
    EXPECT_NE(out.find("orthographic"), std::string::npos) << out;
}

TEST(CameraClipping, NothingNearerThanZnearIsSeen) {
    // An occluder 0.3 before the camera over the whole view: clipped at znear 0.5 the image is the
    // open scene's (light tracing through the lens included: 1% darker if its segments to the lens
    // ran up to the lens), seen at znear 0.1 it is black.
    for (const char* integrator : {"pt", "sppm", "bpt", "vcm"}) {
        SCOPED_TRACE(integrator);
        Image clipped = render("znear_clipped.gltf", integrator, 4), open = render("znear_open.gltf", integrator, 4);
        Image seen = render("znear_seen.gltf", integrator, 4);
        double a = 0, b = 0, s = 0;
        for (size_t i = 0; i < open.rgb.size(); ++i) a += clipped.rgb[i], b += open.rgb[i], s += seen.rgb[i];
        ASSERT_GT(b, 10.0);
        EXPECT_NEAR(a / b, 1.0, 1e-5);
        EXPECT_EQ(s, 0.0);
    }
}
