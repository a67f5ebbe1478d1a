// KHR_materials_anisotropy's loader and end to end (the stretched lobe itself is in
// bsdf_model_test.cpp against a host reference of Heitz 2014's anisotropic GGX: eval,
// reciprocity, chi-square of the visible-normal sampling, weights and white furnaces): the factors
// and texture load, tangents are made for it, and a stretched metal plate renders finite and
// non-negative, alike in the path tracer and SPPM.
#include <gtest/gtest.h>

#include <cmath>

#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

} // namespace

TEST(Anisotropy, LoadsFactorsTextureAndTangents) {
    Scene s = load_gltf(data("aniso_plate.gltf"));
    ASSERT_EQ(s.materials.size(), 1u);
    const dev::Material& m = s.materials[0];
    EXPECT_FLOAT_EQ(m.anisotropy_strength, 0.6f);
    EXPECT_FLOAT_EQ(m.anisotropy_rotation, 0.5f);
    EXPECT_GE(m.anisotropy_tex, 0);
    EXPECT_FALSE(s.tangents.empty()) << "the stretch's direction needs the tangent frame";
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(Anisotropy, StretchedPlateRendersAlikeInPtAndSppm) {
    double mean[2] = {0, 0};
    int k = 0;
    for (const char* integrator : {"pt", "sppm"}) {
        std::string d = make_temp_dir("aniso"), out;
        ASSERT_EQ(run_clppm(data("aniso_plate.gltf") +
                                " --width 16 --height 16 --passes 64 --quiet --no-png "
                                "--integrator " +
                                integrator + " -o " + d + "/i.exr",
                            &out),
                  0)
            << out;
        Image img = read_exr(d + "/i.exr");
        for (float v : img.rgb) {
            ASSERT_TRUE(std::isfinite(v) && v >= 0.f) << integrator;
            mean[k] += v;
        }
        mean[k++] /= double(img.rgb.size());
    }
    EXPECT_GT(mean[0], 0.2);
    EXPECT_NEAR(mean[1] / mean[0], 1.0, 0.03);
}
