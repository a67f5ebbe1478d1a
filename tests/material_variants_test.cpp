// KHR_materials_variants: without --variant a primitive keeps its own material; with one, the
// material its mapping names for that variant; the render lists the file's variants; an unknown
// name is a one-line error listing them.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// tests/data/env_sphere.gltf (a grey sphere under the default white world) with a red and a
// green material as the variants "Red" and "Green".
std::string variant_sphere(const std::string& dir) {
    nlohmann::json g = nlohmann::json::parse(slurp(std::string(CLPPM_TEST_DATA) + "/env_sphere.gltf"));
    for (const auto& [name, rgb] :
         {std::pair<const char*, std::array<double, 3>>{"red", {0.8, 0.1, 0.1}}, {"green", {0.1, 0.8, 0.1}}}) {
        nlohmann::json m = g["materials"][0];
        m["name"] = name;
        m["pbrMetallicRoughness"]["baseColorFactor"] = {rgb[0], rgb[1], rgb[2], 1.0};
        g["materials"].push_back(m);
    }
    g["extensionsUsed"].push_back("KHR_materials_variants");
    g["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "Red"}}, {{"name", "Green"}}};
    g["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}};
    std::ofstream(dir + "/variants.gltf") << g.dump();
    return dir + "/variants.gltf";
}

// The mean colour of the image's middle (the sphere).
std::array<double, 3> middle(const Image& img) {
    std::array<double, 3> sum{};
    int n = 0;
    for (int y = img.height / 3; y < 2 * img.height / 3; ++y)
        for (int x = img.width / 3; x < 2 * img.width / 3; ++x, ++n)
            for (int c = 0; c < 3; ++c)
                sum[size_t(c)] += img.rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3 + size_t(c)];
    for (double& s : sum) s /= n;
    return sum;
}

} // namespace

TEST(MaterialVariants, EachVariantGivesItsMaterialAndTheDefaultKeepsTheFiles) {
    const std::string d = make_temp_dir("variants"), scene = variant_sphere(d);
    std::string out;
    auto render = [&](const std::string& args) {
        EXPECT_EQ(run_clppm(scene + " --width 24 --height 24 --integrator pt --passes 16 --no-png " + args + " -o " +
                                d + "/x.exr",
                            &out),
                  0)
            << out;
        return middle(read_exr(d + "/x.exr"));
    };
    const std::array<double, 3> grey = render(""), red = render("--variant Red"), green = render("--variant Green");
    EXPECT_NE(out.find("material variants: Red, Green; rendering variant Green"), std::string::npos) << out;
    EXPECT_NEAR(grey[0] / grey[1], 1.0, 0.05);
    EXPECT_GT(red[0], 3 * red[1]);
    EXPECT_GT(green[1], 3 * green[0]);
    render("");
    EXPECT_NE(out.find("material variants: Red, Green; rendering the file's default materials"), std::string::npos)
        << out;
    EXPECT_EQ(out.find("KHR_materials_variants is not supported"), std::string::npos) << out;
}

// A mapping to a material or a variant the file does not have is refused whether or not a variant
// is rendered: one line naming the file, the primitive and the mapping.
TEST(MaterialVariants, AMappingToNothingIsAOneLineError) {
    const std::string d = make_temp_dir("variants_mapping"), scene = variant_sphere(d);
    nlohmann::json g = nlohmann::json::parse(slurp(scene));
    const struct {
        const char* what;
        nlohmann::json mapping;
        const char* message;
    } cases[] = {
        {"material 99",
         {{"material", 99}, {"variants", {0}}},
         "mesh 0 primitive 0: KHR_materials_variants mapping 2 names material 99, but the file has 3"},
        {"variant 7",
         {{"material", 1}, {"variants", {7}}},
         "mesh 0 primitive 0: KHR_materials_variants mapping 2 names variant 7, but the file has 2"},
    };
    for (const auto& c : cases) {
        nlohmann::json broken = g;
        broken["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"].push_back(c.mapping);
        std::ofstream(d + "/broken.gltf") << broken.dump();
        for (const std::string variant : {"", " --variant Red"}) {
            std::string out;
            EXPECT_EQ(run_clppm(d + "/broken.gltf" + variant + " -o " + d + "/x.exr", &out), 1) << c.what << variant;
            EXPECT_NE(out.find(c.message), std::string::npos) << c.what << variant << ": " << out;
            EXPECT_NE(out.find("broken.gltf"), std::string::npos) << out;
            EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
        }
    }
}

TEST(MaterialVariants, AnUnknownVariantIsAOneLineErrorListingThem) {
    const std::string d = make_temp_dir("variants_bad"), scene = variant_sphere(d);
    std::string out;
    EXPECT_EQ(run_clppm(scene + " --variant Blue -o " + d + "/x.exr", &out), 1);
    EXPECT_NE(out.find("--variant Blue: no such material variant (the file's: Red, Green)"), std::string::npos) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    EXPECT_EQ(run_clppm("--variant Red -o " + d + "/x.exr", &out), 1);
    EXPECT_NE(out.find("the built-in scene has no material variants"), std::string::npos) << out;
}
