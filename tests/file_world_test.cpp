// A file's own world (scene-level extras.clppm_environment): it lights the scene as the same
// command-line options would, bit for bit; the command line's world replaces it and
// --env-strength / --env-rotate scale and turn it; stderr says which world a render uses; bad
// worlds are one-line errors naming the file.
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

std::string data(const std::string& name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

// tests/data/<scene> with `world` as its scene's extras.clppm_environment, written into dir.
std::string with_world(const std::string& dir, const std::string& scene, const nlohmann::json& world) {
    nlohmann::json g = nlohmann::json::parse(slurp(data(scene)));
    if (!g.contains("scenes")) g["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
    g["scenes"][0]["extras"]["clppm_environment"] = world;
    const std::string path = dir + "/" + scene;
    std::ofstream(path) << g.dump();
    return path;
}

// A 16 x 8 map, bright in one quarter, so that rotation and strength show.
void write_quarter_map(const std::string& path) {
    Image img;
    img.width = 16, img.height = 8;
    img.rgb.assign(16 * 8 * 3, 0.1f);
    for (int y = 0; y < 4; ++y)
        for (int x = 8; x < 12; ++x)
            for (int c = 0; c < 3; ++c) img.rgb[size_t(3 * (y * 16 + x) + c)] = 4.f;
    write_exr(path, img);
}

struct Render {
    int status;
    std::string output;
    Image image;
};

Render render(const std::string& scene, const std::string& args) {
    const std::string d = make_temp_dir("file_world_out"), out_file = d + "/out.exr";
    Render r;
    r.status = run_clppm(
        scene + " --width 24 --height 24 --passes 8 --integrator pt --no-png " + args + " -o " + out_file, &r.output);
    if (r.status == 0) r.image = read_exr(out_file);
    return r;
}

void expect_same(const Render& a, const Render& b) {
    ASSERT_EQ(a.status, 0) << a.output;
    ASSERT_EQ(b.status, 0) << b.output;
    ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
    EXPECT_TRUE(a.image.rgb == b.image.rgb) << "the images differ";
}

} // namespace

TEST(FileWorld, AColourLightsAsEnvColourDoes) {
    const std::string d = make_temp_dir("file_world_color");
    const std::string scene = with_world(d, "env_sphere.gltf", {{"color", {0.5, 0.25, 1.0}}, {"strength", 2.0}});
    const Render file = render(scene, ""), cli = render(data("env_sphere.gltf"), "--env-color 1,0.5,2");
    expect_same(file, cli);
    EXPECT_NE(file.output.find("world: " + scene + ": extras.clppm_environment: colour 0.5,0.25,1 x 2"),
              std::string::npos)
        << file.output;
}

TEST(FileWorld, AMapWithStrengthAndRotationLightsAsTheOptionsDo) {
    const std::string d = make_temp_dir("file_world_map");
    write_quarter_map(d + "/sky.exr");
    const std::string scene =
        with_world(d, "env_floor.gltf", {{"image", "sky.exr"}, {"strength", 3.0}, {"rotation", 90.0}});
    const Render file = render(scene, "");
    expect_same(file, render(data("env_floor.gltf"), "--env " + d + "/sky.exr --env-strength 3 --env-rotate 90"));
    EXPECT_NE(file.output.find("extras.clppm_environment: the map " + d + "/sky.exr, strength 3, rotation 90"),
              std::string::npos)
        << file.output;
    // --env-strength and --env-rotate scale and turn the file's world.
    expect_same(render(scene, "--env-strength 0.5 --env-rotate -30"),
                render(data("env_floor.gltf"), "--env " + d + "/sky.exr --env-strength 1.5 --env-rotate 60"));
}

TEST(FileWorld, TheCommandLinesWorldReplacesIt) {
    const std::string d = make_temp_dir("file_world_override");
    const std::string scene = with_world(d, "env_sphere.gltf", {{"color", {5.0, 5.0, 5.0}}});
    const Render cli = render(scene, "--env-color 1,1,1");
    expect_same(cli, render(data("env_sphere.gltf"), "--env-color 1,1,1"));
    EXPECT_NE(cli.output.find("world: --env-color"), std::string::npos) << cli.output;
    // --no-default-light: no world at all; this scene has no lights of its own, so it is refused.
    const Render none = render(scene, "--no-default-light");
    EXPECT_EQ(none.status, 1);
    EXPECT_NE(none.output.find("no lights"), std::string::npos) << none.output;
}

TEST(FileWorld, ABlackWorldIsNoneAndALightlessSceneIsRefused) {
    const std::string d = make_temp_dir("file_world_black");
    const Render r = render(with_world(d, "env_sphere.gltf", {{"color", {0, 0, 0}}}), "");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("no lights"), std::string::npos) << r.output;
    // Without a world of its own a lightless scene gets the default one, and says so.
    const Render plain = render(data("env_sphere.gltf"), "");
    EXPECT_EQ(plain.status, 0) << plain.output;
    EXPECT_NE(plain.output.find("world: the default environment"), std::string::npos) << plain.output;
}

TEST(FileWorld, BadWorldsAreOneLineErrorsNamingTheFile) {
    const std::string d = make_temp_dir("file_world_bad");
    write_quarter_map(d + "/sky.exr");
    const std::pair<nlohmann::json, const char*> cases[] = {
        {"white", "must be an object"},
        {{{"color", {1, 1}}}, ".color must be [r, g, b]"},
        {{{"color", {1, -1, 1}}}, "must be a finite number >= 0"},
        {{{"color", {1, 1, 1}}, {"image", "sky.exr"}}, "either \"color\" or \"image\""},
        {{{"colour", {1, 1, 1}}}, "unknown key \"colour\""},
        {{{"image", "../sky.exr"}}, "lies outside the scene's folder"},
        {{{"image", "missing.exr"}}, "missing.exr"},
        {{{"image", "env_sphere.gltf"}}, "not an equirectangular .exr or .hdr file"},
        {{{"image", "sky.exr"}, {"strength", "2"}}, ".strength must be a number"},
        {{{"color", {1, 1, 1}}, {"rotation", {90}}}, ".rotation must be a number"},
    };
    for (const auto& [world, expected] : cases) {
        const std::string sub = make_temp_dir("file_world_bad_case");
        const std::string scene = with_world(sub, "env_sphere.gltf", world);
        const Render r = render(scene, "");
        EXPECT_EQ(r.status, 1) << world.dump();
        EXPECT_NE(r.output.find(expected), std::string::npos) << world.dump() << "\n" << r.output;
        EXPECT_NE(r.output.find(scene), std::string::npos) << "names the file: " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
    }
}
