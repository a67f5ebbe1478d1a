// An area light's spread (material extras "clppm_area_light_spread", as Blender's area lights
// have it and Cycles models it): the floor under a small emitter with a spread of 60 degrees is
// lit f(0) = tan h / (tan h - h) times more than under a Lambertian one (h half the spread), as an
// independent host integral of the formula over the emitter says, through the path tracer
// (light samples and BSDF hits under MIS), SPPM's photons alone, and VCM; a scene without a
// spread builds kernels without it; a bad spread is a one-line error.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string scene(const std::string& dir, const nlohmann::json& spread) {
    nlohmann::json g = nlohmann::json::parse(slurp(std::string(CLPPM_TEST_DATA) + "/spread_light.gltf"));
    for (nlohmann::json& m : g["materials"])
        if (m["name"] == "lamp" && !spread.is_null()) m["extras"]["clppm_area_light_spread"] = spread;
    const std::string path = dir + "/spread.gltf";
    std::ofstream(path) << g.dump();
    return path;
}

// The floor's radiance under the emitter's centre by the formula, integrated over the emitter
// (0.1 x 0.1 at height 5, radiance 100; floor albedo 0.5): albedo / pi int L f(a) cos^2 / r^2 dA.
double reference(double spread_degrees) {
    const double h = 0.5 * spread_degrees * M_PI / 180, t = std::tan(h);
    const int n = 400;
    double e = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = -0.05 + 0.1 * (i + 0.5) / n, z = -0.05 + 0.1 * (j + 0.5) / n;
            const double r2 = x * x + z * z + 25, cos_a = 5 / std::sqrt(r2);
            const double tan_a = std::sqrt(x * x + z * z) / 5;
            const double f = spread_degrees >= 180 ? 1.0 : std::max(t - tan_a, 0.0) / (t - h);
            e += 100 * f * cos_a * cos_a / r2 * (0.01 / (n * n));
        }
    return 0.5 / M_PI * e;
}

double centre(const std::string& file, const std::string& args, std::string* out) {
    const std::string exr = make_temp_dir("spread_out") + "/x.exr";
    EXPECT_EQ(run_clppm(file + " --width 32 --height 32 --no-png " + args + " -o " + exr, out), 0) << *out;
    const Image img = read_exr(exr);
    double s = 0;
    for (int y = 14; y < 18; ++y)
        for (int x = 14; x < 18; ++x)
            for (int c = 0; c < 3; ++c) s += img.rgb[size_t((y * 32 + x) * 3 + c)];
    return s / 48;
}

} // namespace

TEST(EmissionSpread, TheFloorUnderASpreadLightIsLitAsTheFormulaSays) {
    const std::string d = make_temp_dir("spread");
    const double lambertian = reference(180), spread = reference(60);
    EXPECT_NEAR(spread / lambertian, std::tan(M_PI / 6) / (std::tan(M_PI / 6) - M_PI / 6), 0.2); // f(0) = 10.74
    std::string out;
    const std::string plain = scene(d, nullptr);
    EXPECT_NEAR(centre(plain, "--integrator pt --passes 64", &out) / lambertian, 1.0, 0.01);
    EXPECT_EQ(out.find("emission spread"), std::string::npos) << "a scene without a spread pays nothing: " << out;
    const std::string narrow = scene(d, 60.0);
    const double pt = centre(narrow, "--integrator pt --passes 64", &out);
    EXPECT_NE(out.find("emission spread"), std::string::npos) << out;
    EXPECT_NEAR(pt / spread, 1.0, 0.02) << "path tracer";
    EXPECT_NEAR(centre(narrow, "--integrator sppm --direct photons --passes 16 --photons 200000", &out) / spread, 1.0,
                0.05)
        << "SPPM, photons alone";
    EXPECT_NEAR(centre(narrow, "--integrator vcm --passes 32", &out) / spread, 1.0, 0.03) << "VCM";
    // 180 degrees is the Lambertian emitter, with the same kernels as no spread at all.
    EXPECT_NEAR(centre(scene(d, 180.0), "--integrator pt --passes 64", &out) / lambertian, 1.0, 0.01);
    EXPECT_EQ(out.find("emission spread"), std::string::npos) << out;
}

TEST(EmissionSpread, ABadSpreadIsAOneLineError) {
    const std::string d = make_temp_dir("spread_bad");
    for (const nlohmann::json& bad : {nlohmann::json(0.0), nlohmann::json(181.0), nlohmann::json("wide")}) {
        std::string out;
        EXPECT_EQ(run_clppm(scene(d, bad) + " -o " + d + "/x.exr", &out), 1) << bad.dump();
        EXPECT_NE(out.find("extras.clppm_area_light_spread must be a number of degrees in (0, 180]"), std::string::npos)
            << out;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    }
}
