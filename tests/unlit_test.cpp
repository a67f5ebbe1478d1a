// KHR_materials_unlit: an unlit surface shows its base colour as it is (factor times COLOR_0
// here), whatever lights the scene, and it lights nothing: the wall beside and behind it renders
// bit for bit as it does when the panel's colour is 0, in every integrator (the panel only
// shadows it). tests/data/unlit_panel.gltf and unlit_dark.gltf (tests/data/make_test_gltf.py).
#include <gtest/gtest.h>

#include <cmath>

#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

Image render(const char* file, const char* integrator) {
    std::string d = make_temp_dir("unlit"), out;
    const std::string args = data(file) + " --width 32 --height 32 --passes 3 --quiet --no-png --integrator " +
                             integrator + " -o " + d + "/i.exr";
    EXPECT_EQ(run_clppm(args, &out), 0) << out;
    return read_exr(d + "/i.exr");
}

float px(const Image& img, int x, int y, int c) { return img.rgb[size_t(3 * (y * img.width + x) + c)]; }

} // namespace

TEST(Unlit, LoadsAsUnlitWithoutLobesOrWarnings) {
    Scene s = load_gltf(data("unlit_panel.gltf"));
    ASSERT_EQ(s.materials.size(), 2u);
    const dev::Material& panel = s.materials[1];
    EXPECT_TRUE(panel.flags & MATERIAL_FLAG_UNLIT);
    EXPECT_EQ(panel.metallic, 0.f) << "metallicFactor 1 of the file is no lobe of an unlit surface";
    EXPECT_EQ(panel.specular_color[3], 0.f);
    EXPECT_FALSE(s.materials[0].flags & MATERIAL_FLAG_UNLIT);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(Unlit, ShowsTheBaseColourAndLightsNothing) {
    // Base colour (0.2, 0.5, 0.8) times COLOR_0 (1, 0.5, 1). The panel covers columns 0-13 and
    // rows 4-28 of the 32 x 32 image; columns 16 on are the lit wall only.
    const float shown[3] = {0.2f, 0.25f, 0.8f};
    for (const char* integrator : {"pt", "sppm", "pppm", "ppm", "vcm", "bpt"}) {
        SCOPED_TRACE(integrator);
        Image lit = render("unlit_panel.gltf", integrator), dark = render("unlit_dark.gltf", integrator);
        for (int y = 6; y < 26; ++y)
            for (int x = 1; x < 12; ++x)
                for (int c = 0; c < 3; ++c) {
                    ASSERT_NEAR(px(lit, x, y, c), shown[c], 1e-5f) << x << "," << y << " channel " << c;
                    ASSERT_EQ(px(dark, x, y, c), 0.f) << "an unlit black panel is black, however lit";
                }
        double wall = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 16; x < 32; ++x)
                for (int c = 0; c < 3; ++c) {
                    ASSERT_EQ(px(lit, x, y, c), px(dark, x, y, c)) << x << "," << y << ": the panel lit the wall";
                    wall += px(lit, x, y, c);
                }
        EXPECT_GT(wall, 1.0) << "the wall is lit by the point light";
    }
}

TEST(Unlit, RendersWithNothingButUnlitSurfaces) {
    // No lights and a black world: the unlit panel is still seen, in its colour, by every
    // integrator; the wall is black. (A scene with nothing unlit and no light stays refused:
    // cli_test.cpp.)
    const float shown[3] = {0.2f, 0.25f, 0.8f};
    for (const char* integrator : {"pt", "sppm", "pppm", "ppm", "vcm", "bpt"}) {
        SCOPED_TRACE(integrator);
        Image img = render("unlit_alone.gltf", integrator);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                for (int c = 0; c < 3; ++c) {
                    const bool panel = y >= 6 && y < 26 && x >= 1 && x < 12;
                    const float v = px(img, x, y, c);
                    ASSERT_TRUE(std::isfinite(v)) << x << "," << y;
                    if (panel) {
                        ASSERT_NEAR(v, shown[c], 1e-5f) << x << "," << y << " channel " << c;
                    }
                    if (x >= 16) {
                        ASSERT_EQ(v, 0.f) << x << "," << y << ": nothing lights the wall";
                    }
                }
    }
}
