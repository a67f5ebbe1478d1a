// KHR_materials_iridescence's thin-film Fresnel (kernels/iridescence.cl): the kernel against a
// host reference in double; the approximation against the exact spectral Airy reflectance at
// normal incidence (CIE 1931 averaged, within 0.025 over films 100-800 nm of index 1.3 and 2.0:
// the colours are right); the thick-film limit, where interference averages out, against the
// incoherent sum R12 + T^2 R23 / (1 - R12 R23) in closed form; and a film of thickness 0 as the
// bare base at normal incidence (within the approximation's 0.008). The loader and the BSDF with a film are in
// material tests below and in bsdf_model_test.cpp.
#include <gtest/gtest.h>

#include "bsdf_kernels.h"
#include "io/image_io.h"
#include "iridescence_reference.h"
#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

TEST(Iridescence, KernelMatchesTheHostReference) {
    std::vector<float> in;
    std::vector<std::array<double, 6>> cases;
    for (double eta2 : {1.0, 1.3, 1.8, 2.5})
        for (double d : {0.0, 0.02, 120.0, 400.0, 900.0})
            for (double c : {1.0, 0.7, 0.3, 0.05})
                for (double f0 : {0.04, 0.5, 0.95}) {
                    cases.push_back({eta2, d, c, f0, f0 * 0.8, f0 * 0.3});
                    for (double v : cases.back()) in.push_back(float(v));
                }
    std::vector<float> out = bsdf::device().irid(in);
    for (size_t i = 0; i < cases.size(); ++i) {
        const auto& p = cases[i];
        Rgb want = ref_irid_fresnel(float(p[0]), float(p[1]), float(p[2]), {float(p[3]), float(p[4]), float(p[5])});
        for (size_t k = 0; k < 3; ++k)
            ASSERT_NEAR(out[3 * i + k], want[k], 2e-4 + 1e-3 * want[k])
                << "eta2 " << p[0] << " d " << p[1] << " cos " << p[2] << " f0 " << p[3] << " channel " << k;
    }
}

TEST(Iridescence, AgreesWithTheSpectralAiryFormulaAtNormalIncidence) {
    for (double n2 : {1.3, 2.0})
        for (double d = 100; d <= 800; d += 50) {
            Rgb model = ref_irid_fresnel(n2, d, 1.0, {0.04, 0.04, 0.04}); // base of index 1.5
            Rgb airy = airy_rgb_normal(n2, 1.5, d);
            for (size_t k = 0; k < 3; ++k)
                EXPECT_NEAR(model[k], airy[k], 0.025) << "film " << n2 << " d " << d << " channel " << k;
        }
}

TEST(Iridescence, ThickFilmsAverageToTheIncoherentSum) {
    for (double n2 : {1.3, 2.0})
        for (double c : {1.0, 0.6, 0.2}) {
            Rgb model = ref_irid_fresnel(n2, 5000, c, {0.04, 0.04, 0.04});
            const double r0 = (n2 - 1) / (n2 + 1), R12 = ref_schlick(r0 * r0, c);
            const double cos2 = std::sqrt(1 - (1 - c * c) / (n2 * n2)), r1 = (1.5 - n2) / (1.5 + n2);
            const double R23 = ref_schlick(r1 * r1, cos2);
            const double incoherent = R12 + (1 - R12) * (1 - R12) * R23 / (1 - R12 * R23);
            for (double v : model) EXPECT_NEAR(v, incoherent, 1e-4) << "film " << n2 << " cos " << c;
        }
}

TEST(Iridescence, AFilmOfNoThicknessIsTheBareBaseAtNormalIncidence) {
    // Only there: the film's index fades to 1, but Schlick's R12 for F0 = 0 is still (1 - cos)^5,
    // so the approximation keeps a film at oblique views (0.19 instead of 0.07 at 60 degrees).
    for (double c : {1.0})
        for (double f0 : {0.04, 0.9}) {
            Rgb model = ref_irid_fresnel(1.3, 0.0, c, {f0, f0, f0});
            for (double v : model) EXPECT_NEAR(v, ref_schlick(f0, c), 0.008) << "cos " << c << " f0 " << f0;
        }
}

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

} // namespace

TEST(Iridescence, LoadsFactorsAndTextures) {
    Scene s = load_gltf(data("film_textured.gltf"));
    ASSERT_EQ(s.materials.size(), 1u);
    const dev::Material& m = s.materials[0];
    EXPECT_FLOAT_EQ(m.iridescence, 0.8f);
    EXPECT_FLOAT_EQ(m.iridescence_ior, 1.8f);
    EXPECT_FLOAT_EQ(m.iridescence_thickness[0], 200.f);
    EXPECT_FLOAT_EQ(m.iridescence_thickness[1], 600.f);
    EXPECT_GE(m.iridescence_tex, 0);
    EXPECT_GE(m.iridescence_thickness_tex, 0);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
    const dev::Material d = load_gltf(data("film_plate.gltf")).materials[0]; // a copy: the scene is a temporary
    EXPECT_FLOAT_EQ(d.iridescence_ior, 1.3f) << "the extension's defaults";
    EXPECT_FLOAT_EQ(d.iridescence_thickness[0], 100.f);
    EXPECT_EQ(d.iridescence_thickness_tex, -1);
}

TEST(Iridescence, SmoothFilmedPlateShowsTheFilmsReflectanceInEveryIntegrator) {
    // Black base, ior 1.5 (F0 0.04), a film of 1.3 and 400 nm, seen head-on in a white world: the
    // mirror layer shows F_film(1) exactly, channel by channel.
    const Rgb want = ref_irid_fresnel(1.3, 400.0, 1.0, {0.04, 0.04, 0.04});
    for (const char* integrator : {"pt", "sppm", "vcm"}) {
        SCOPED_TRACE(integrator);
        std::string d = make_temp_dir("film"), out;
        ASSERT_EQ(run_clppm(data("film_plate.gltf") +
                                " --width 8 --height 8 --passes 2 --quiet --no-png --integrator " + integrator +
                                " -o " + d + "/i.exr",
                            &out),
                  0)
            << out;
        Image img = read_exr(d + "/i.exr");
        for (size_t i = 0; i < img.rgb.size(); ++i)
            ASSERT_NEAR(img.rgb[i], want[i % 3], 2e-3 * want[i % 3] + 1e-4)
                << "pixel " << i / 3 << " channel " << i % 3;
    }
}
