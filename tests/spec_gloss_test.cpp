// KHR_materials_pbrSpecularGlossiness (archived), converted to metallic-roughness with
// KHR_materials_specular and KHR_materials_ior: its factors render bit for bit as the
// metallic-roughness material the conversion names (README, "glTF support"); a
// specularGlossinessTexture gives the same image as its values as factors; the conversion is
// said once.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

const double kF0 = std::pow(999.0 / 1001.0, 2); // the F0 of IOR 1000

// tests/data/mr_texture.gltf (a textured plate under a light) with material 0 replaced.
std::string plate_with(const std::string& dir, const std::string& name, const nlohmann::json& material) {
    nlohmann::json g = nlohmann::json::parse(slurp(std::string(CLPPM_TEST_DATA) + "/mr_texture.gltf"));
    g["materials"][0] = material;
    g["images"].push_back({{"uri", "sg.png"}});
    g["textures"].push_back({{"source", 1}});
    std::ofstream(dir + "/" + name) << g.dump();
    return dir + "/" + name;
}

struct Result {
    std::string output;
    Image image;
};

Result render(const std::string& scene) {
    Result r;
    const std::string out_file = make_temp_dir("spec_gloss_out") + "/x.exr";
    EXPECT_EQ(
        run_clppm(scene + " --width 24 --height 24 --integrator pt --passes 32 --no-png -o " + out_file, &r.output), 0)
        << r.output;
    r.image = read_exr(out_file);
    return r;
}

double mean(const Image& img) {
    double s = 0;
    for (float v : img.rgb) s += v;
    return s / double(img.rgb.size());
}

} // namespace

TEST(SpecGloss, FactorsRenderAsTheMetallicRoughnessMaterialTheyConvertTo) {
    const std::string d = make_temp_dir("spec_gloss");
    const std::vector<double> diffuse{0.5, 0.4, 0.3, 1.0}, specular{0.2, 0.15, 0.1};
    const Result sg = render(
        plate_with(d, "sg.gltf",
                   {{"name", "sg"},
                    {"extensions",
                     {{"KHR_materials_pbrSpecularGlossiness",
                       {{"diffuseFactor", diffuse}, {"specularFactor", specular}, {"glossinessFactor", 0.7}}}}}}));
    const Result mr = render(plate_with(
        d, "mr.gltf",
        {{"name", "mr"},
         {"pbrMetallicRoughness", {{"baseColorFactor", diffuse}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.3}}},
         {"extensions",
          {{"KHR_materials_ior", {{"ior", 1000.0}}},
           {"KHR_materials_specular",
            {{"specularFactor", 1.0},
             {"specularColorFactor", {specular[0] / kF0, specular[1] / kF0, specular[2] / kF0}}}}}}}));
    ASSERT_EQ(sg.image.rgb.size(), mr.image.rgb.size());
    EXPECT_TRUE(sg.image.rgb == mr.image.rgb) << "means " << mean(sg.image) << " and " << mean(mr.image);
    EXPECT_NE(sg.output.find("1 material(s) in KHR_materials_pbrSpecularGlossiness (archived) converted"),
              std::string::npos)
        << sg.output;
    EXPECT_EQ(sg.output.find("not supported"), std::string::npos) << sg.output;
}

TEST(SpecGloss, ItsTextureGivesWhatItsValuesGiveAsFactors) {
    const std::string d = make_temp_dir("spec_gloss_tex");
    // A uniform texture: specular (0.6, 0.6, 0.6) in sRGB, glossiness 0.8 in alpha.
    const unsigned char texel[4] = {203, 203, 203, 204}; // sRGB 203/255 = 0.5972 linear; 204/255 = 0.8
    unsigned char px[4 * 4];
    for (int i = 0; i < 4; ++i) std::copy(texel, texel + 4, px + 4 * i);
    ASSERT_NE(stbi_write_png((d + "/sg.png").c_str(), 2, 2, 4, px, 8), 0);
    const double spec = std::pow((203 / 255.0 + 0.055) / 1.055, 2.4);
    const Result tex = render(
        plate_with(d, "tex.gltf",
                   {{"name", "tex"},
                    {"extensions",
                     {{"KHR_materials_pbrSpecularGlossiness",
                       {{"diffuseFactor", {0.5, 0.5, 0.5, 1.0}}, {"specularGlossinessTexture", {{"index", 1}}}}}}}}));
    const Result factors = render(plate_with(d, "factors.gltf",
                                             {{"name", "factors"},
                                              {"extensions",
                                               {{"KHR_materials_pbrSpecularGlossiness",
                                                 {{"diffuseFactor", {0.5, 0.5, 0.5, 1.0}},
                                                  {"specularFactor", {spec, spec, spec}},
                                                  {"glossinessFactor", 0.8}}}}}}));
    // The texture is 8 bits (roughness 51/255 = 0.2 exactly; the colour 1/255 steps): within 0.5%.
    EXPECT_NEAR(mean(tex.image) / mean(factors.image), 1.0, 0.005);
    EXPECT_GT(mean(tex.image), 0.0);
}
