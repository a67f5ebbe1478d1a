// clppm against an independent renderer: the scenes of tests/data/make_test_gltf.py's
// reference_scenes() (a rough glass block, a tinted absorbing glass block, a textured floor with
// a cut-out leaf card, a normal-mapped wall) against Mitsuba 3
// images committed under tests/references/ (make_references.py made them, 65536 samples per
// pixel, from the same glTF files). Both the path tracer and SPPM must agree with them in mean
// and, box-filtered over 4 x 4 pixels (so that the comparison measures bias, not the noise of a
// short render), in relative MSE. bench/RESULTS.md records the same numbers at longer renders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/image_compare.h"
#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

struct Agreement {
    double mean_ratio, box4_rel_mse;
};

Agreement render_against_reference(const std::string& scene, const std::string& args) {
    const std::string d = make_temp_dir("reference"), out_file = d + "/out.exr";
    std::string out;
    EXPECT_EQ(run_clppm(std::string(CLPPM_TEST_DATA) + "/" + scene + ".gltf --width 64 --height 64 --quiet --no-png " +
                            args + " -o " + out_file,
                        &out),
              0)
        << out;
    const Image a = read_exr(out_file);
    const Image ref = read_exr(std::string(CLPPM_TEST_DATA) + "/../references/" + scene + ".exr");
    const ImageDifference full = compare_images(a, ref);
    EXPECT_EQ(full.nonfinite_a, 0u);
    const ImageDifference box = compare_images(box_filter(a, 4), box_filter(ref, 4));
    std::printf("%s %s: mean ratio %.4f, box-4 relative MSE %.5f\n", scene.c_str(), args.c_str(),
                full.mean_a / full.mean_b, box.rel_mse);
    return {full.mean_a / full.mean_b, box.rel_mse};
}

// Both integrators against the scene's reference: the mean within 1% (the reference's own noise is
// below 0.1%); box-4 relative MSE 5e-4 for the path tracer and 3e-3 for SPPM (whose density
// estimate blurs edges at 64 x 64).
void expect_agreement(const std::string& scene) {
    for (const char* integrator : {"pt", "sppm"}) {
        const bool pt = std::string(integrator) == "pt";
        Agreement g = render_against_reference(scene, std::string("--integrator ") + integrator +
                                                          (pt ? " --passes 2048" : " --passes 48 --photons 100000"));
        EXPECT_NEAR(g.mean_ratio, 1.0, 0.01) << integrator;
        EXPECT_LT(g.box4_rel_mse, pt ? 5e-4 : 3e-3) << integrator;
    }
}

} // namespace

// Measured at these settings (two cores, PoCL): rough glass PT 0.9979 and 6e-5, SPPM 1.0006 and 1.1e-3;
// tinted volume PT 1.0008 and 7e-5, SPPM 0.9995 and 3.2e-4; textured floor and leaf card PT
// 1.0004 and 3e-5, SPPM 0.9997 and 1.2e-4.
TEST(ReferenceImages, RoughGlassAgreesWithMitsuba) { expect_agreement("ref_rough_glass"); }

TEST(ReferenceImages, TintedVolumeAgreesWithMitsuba) { expect_agreement("ref_tinted_volume"); }

// Textures against Mitsuba's bitmaps: a floor whose sRGB base colour texture repeats three times
// (REPEAT, bilinear), and a leaf card cut out by its texture's alpha (alphaMode MASK), in shadow
// and in view.
TEST(ReferenceImages, TexturedFloorAndLeafCardAgreeWithMitsuba) { expect_agreement("ref_textured"); }

// A wall whose normal map tilts by 31 degrees up, down, left and right (no TANGENT: clppm's
// generated frame), lit from a lamp above it at grazing angles, so a mirrored or swapped frame,
// a wrongly decoded map or a lost scale shows: Mitsuba's `normalmap` without its terminator
// shadowing (make_references.py says why). What is left is a convention glTF does not fix: where
// a ray meets the wall from below its mapped normal (from the floor, at grazing angles, never from
// the camera here), clppm shades with the geometric normal and Mitsuba returns black. clppm
// rendered with Mitsuba's convention instead agrees to 1.0004 in mean and 1.7e-5 box-4 relative
// MSE (PT); as shipped PT gives 1.0052 and 6.9e-5, SPPM 1.0045 and 1.2e-3, the excess in the
// rows where wall and floor meet.
TEST(ReferenceImages, NormalMappedWallAgreesWithMitsuba) { expect_agreement("ref_normal_panel"); }

namespace {

// The measure --target-error states, computed here independently: the 90th percentile over
// pixels of |Y - Y_ref| / max(Y_ref, 1% of the mean Y_ref), on luminance.
double p90_relative_error(const Image& a, const Image& ref) {
    std::vector<double> ya, yr;
    double mean = 0;
    for (size_t i = 0; i < ref.rgb.size() / 3; ++i) {
        auto y = [&](const Image& im) {
            return 0.2126 * im.rgb[3 * i] + 0.7152 * im.rgb[3 * i + 1] + 0.0722 * im.rgb[3 * i + 2];
        };
        ya.push_back(y(a)), yr.push_back(y(ref));
        mean += yr.back();
    }
    mean /= double(yr.size());
    std::vector<double> rel;
    for (size_t i = 0; i < ya.size(); ++i) rel.push_back(std::fabs(ya[i] - yr[i]) / std::max(yr[i], 0.01 * mean));
    std::sort(rel.begin(), rel.end());
    return rel[size_t(std::ceil(0.9 * double(rel.size()))) - 1];
}

} // namespace

// The stopping rule against Mitsuba (bench/ERROR_CALIBRATION.md fits its factor against SPPM
// references): when --target-error E stops a render, the image's actual error, by the measure the
// option states, lies in [E/2, E], for each integrator, on the textured floor and
// on the rough glass block, a scene the calibration never saw; the path tracer's, VCM's and BPT's
// estimates are their noise alone. PPM's four fixed samples per pixel
// cannot reach 0.15 on the rough glass (blurred refraction varies within a pixel): there it must
// not stop, and it is right not to.
TEST(ReferenceImages, TargetErrorStopsWithinTheStatedBand) {
    struct Case {
        const char* scene;
        const char* integrator;
        double target;
        bool reachable;
    };
    for (const Case& c : {Case{"ref_textured", "ppm", 0.1, true}, Case{"ref_textured", "sppm", 0.1, true},
                          Case{"ref_textured", "pppm", 0.1, true}, Case{"ref_textured", "pt", 0.1, true},
                          Case{"ref_rough_glass", "pt", 0.15, true}, Case{"ref_rough_glass", "sppm", 0.15, true},
                          Case{"ref_rough_glass", "pppm", 0.15, true}, Case{"ref_rough_glass", "ppm", 0.15, false},
                          Case{"ref_textured", "vcm", 0.1, true}, Case{"ref_textured", "bpt", 0.1, true},
                          Case{"ref_rough_glass", "vcm", 0.15, true}, Case{"ref_rough_glass", "bpt", 0.15, true}}) {
        const std::string what = std::string(c.scene) + " " + c.integrator;
        const Image ref = read_exr(std::string(CLPPM_TEST_DATA) + "/../references/" + c.scene + ".exr");
        const std::string d = make_temp_dir("target_error"), out_file = d + "/out.exr";
        std::string out;
        ASSERT_EQ(run_clppm(std::string(CLPPM_TEST_DATA) + "/" + c.scene + ".gltf --width 64 --height 64 --quiet " +
                                "--no-png --photons 50000 --passes " + (c.reachable ? "2000" : "60") +
                                " --integrator " + c.integrator + " --target-error " + std::to_string(c.target) +
                                " --stats-json " + d + "/stats.json -o " + out_file,
                            &out),
                  0)
            << out;
        std::ifstream in(d + "/stats.json");
        const nlohmann::json j = nlohmann::json::parse(in);
        // Out of reach, the user is told why.
        EXPECT_EQ(out.find("out of PPM's reach") != std::string::npos, !c.reachable) << what << ": " << out;
        const Image img = read_exr(out_file);
        const double actual = p90_relative_error(img, ref);
        EXPECT_NEAR(compare_images(img, ref).p90_rel_error, actual, 1e-9 * actual); // clppm compare's figure
        std::printf("%s: --target-error %.2f, %d passes, estimate %.4f, actual %.4f\n", what.c_str(), c.target,
                    j["passes"].get<int>(), j["error"]["estimated"].get<double>(), actual);
        EXPECT_EQ(j["error"]["reached"].get<bool>(), c.reachable) << what;
        if (c.reachable) {
            EXPECT_LE(actual, c.target) << what;
            EXPECT_GE(actual, 0.5 * c.target) << what;
        } else {
            EXPECT_GT(actual, c.target) << what;
            EXPECT_GT(j["error"]["estimated"].get<double>(), 0.5 * actual) << what;
        }
    }
}
