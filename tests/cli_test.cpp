// The clppm command as a user meets it: exit codes, one-line errors that name the file or
// option, the files a render writes, and images that do not depend on the work-group size.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const std::string& name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }
std::string scene(const std::string& name) { return std::string(CLPPM_SCENES_DIR) + "/" + name; }

bool exists(const std::string& path) {
    struct stat st;
    return ::stat(path.c_str(), &st) == 0;
}

// The message a failing clppm prints: exactly one line starting with "clppm: error: ".
void expect_one_line_error(const std::string& out, const std::string& must_contain) {
    EXPECT_EQ(out.rfind("clppm: error: ", 0), 0u) << out;
    EXPECT_NE(out.find(must_contain), std::string::npos) << out;
    EXPECT_EQ(out.find('\n'), out.size() - 1) << "more than one line:\n" << out;
}

const char* kSmall = " --width 24 --height 24 --passes 2 --photons 5000 --quiet";

} // namespace

TEST(Cli, RendersTheDefaultSceneToExrAndPng) {
    std::string dir = make_temp_dir("cli"), out;
    ASSERT_EQ(run_clppm("-o " + dir + "/c.exr --stats-json " + dir + "/s.json" + kSmall, &out), 0) << out;
    ASSERT_TRUE(exists(dir + "/c.exr"));
    ASSERT_TRUE(exists(dir + "/c.png"));
    Image img = read_exr(dir + "/c.exr");
    EXPECT_EQ(img.width, 24);
    EXPECT_EQ(img.height, 24);
    EXPECT_EQ(count_nonfinite(img), 0u);
    EXPECT_GT(mean_radiance(img), 0.01);
    std::ifstream js(dir + "/s.json");
    std::string json((std::istreambuf_iterator<char>(js)), std::istreambuf_iterator<char>());
    for (const char* key : {"\"passes\": 2", "\"passes_per_second\"", "\"phase_seconds\"", "\"device\"", "\"bvh\""})
        EXPECT_NE(json.find(key), std::string::npos) << key << " missing in\n" << json;
}

// Without --integrator the scene decides (cli/default_integrator.h, measured in bench/RESULTS.md):
// VCM where glass casts caustics of the scene's lights (the built-in Cornell box), the path
// tracer, with 512 passes, for a diffuse scene; the note says which and why.
TEST(Cli, DefaultIntegratorDependsOnTheLights) {
    const std::string dir = make_temp_dir("cli");
    std::string out;
    ASSERT_EQ(
        run_clppm("--width 16 --height 16 --passes 2 --no-png -o " + dir + "/a.exr --stats-json " + dir + "/a.json",
                  &out),
        0)
        << out;
    EXPECT_NE(out.find("integrator vcm: material glass (glass or smooth metal) casts caustics"), std::string::npos)
        << out;
    std::ifstream a(dir + "/a.json");
    EXPECT_EQ(nlohmann::json::parse(a)["integrator"], "vcm");
    // A diffuse plane under a point light: nothing casts a caustic.
    ASSERT_EQ(run_clppm(scene("plane_point_light.gltf") + " --width 8 --height 8 --no-png -o " + dir +
                            "/c.exr --stats-json " + dir + "/c.json",
                        &out),
              0)
        << out;
    EXPECT_NE(out.find("integrator pt: no glass or smooth metal casts caustics"), std::string::npos) << out;
    ASSERT_EQ(run_clppm(data("embedded.gltf") + " --width 8 --height 8 --no-png -o " + dir + "/b.exr --stats-json " +
                            dir + "/b.json",
                        &out),
              0)
        << out;
    EXPECT_NE(out.find("integrator pt: the scene is lit only by its environment"), std::string::npos) << out;
    std::ifstream b(dir + "/b.json");
    const nlohmann::json jb = nlohmann::json::parse(b);
    EXPECT_EQ(jb["integrator"], "pt");
    EXPECT_EQ(jb["passes"].get<int>(), 512);
}

// The path tracer cannot find a spot light's caustic through glass: asked for on such a scene, it
// says so; on the Cornell box (an area light: its caustic is found by BSDF sampling) it does not.
TEST(Cli, PathTracerWarnsOfCausticsItCannotFind) {
    const std::string dir = make_temp_dir("cli");
    std::string out;
    ASSERT_EQ(run_clppm(std::string(CLPPM_SCENES_DIR) +
                            "/caustic.gltf --integrator pt --passes 1 --width 8 "
                            "--height 8 --quiet --no-png -o " +
                            dir + "/c.exr",
                        &out),
              0)
        << out;
    EXPECT_NE(out.find("warning: the path tracer cannot find caustics of point, spot or directional lights"),
              std::string::npos)
        << out;
    ASSERT_EQ(run_clppm("--integrator pt --passes 1 --width 8 --height 8 --quiet --no-png -o " + dir + "/d.exr", &out),
              0)
        << out;
    EXPECT_EQ(out.find("warning"), std::string::npos) << out;
}

// The default render anti-aliases and its mean is right where a light's edge is in view (the
// Cornell box's ceiling light): within 1% of the path tracer's (unbiased; it agrees with Mitsuba
// in reference_images_test) at 64 x 64. PPM with one hit point per pixel, the old default, was
// 5.7% off here.
TEST(Cli, DefaultRenderMeanMatchesTheReference) {
    const std::string dir = make_temp_dir("cli");
    std::string out;
    ASSERT_EQ(run_clppm("--width 64 --height 64 --quiet --no-png -o " + dir + "/d.exr", &out), 0) << out;
    ASSERT_EQ(run_clppm("--width 64 --height 64 --quiet --no-png --integrator pt --passes 2048 --seed 9 -o " + dir +
                            "/ref.exr",
                        &out),
              0)
        << out;
    ASSERT_EQ(run_clppm("compare " + dir + "/d.exr " + dir + "/ref.exr", &out), 0) << out;
    const nlohmann::json j = nlohmann::json::parse(out.substr(out.find('{')));
    std::printf("default render against the path tracer: mean ratio %.4f, p90 relative error %.4f\n",
                j["mean_ratio"].get<double>(), j["p90_rel_error"].get<double>());
    EXPECT_NEAR(j["mean_ratio"].get<double>(), 1.0, 0.01);
}

TEST(Cli, NoPngWritesOnlyTheExr) {
    std::string dir = make_temp_dir("cli"), out;
    ASSERT_EQ(run_clppm("-o " + dir + "/c.exr --no-png" + std::string(kSmall), &out), 0) << out;
    EXPECT_TRUE(exists(dir + "/c.exr"));
    EXPECT_FALSE(exists(dir + "/c.png"));
}

// Same seed, same device: the same image bit for bit, whatever the work-group size and however
// many batches a pass's photons are traced in.
TEST(Cli, ImageDoesNotDependOnWorkGroupSizeOrPhotonBatches) {
    for (const char* integrator : {"ppm", "sppm"}) {
        std::string dir = make_temp_dir("cli"), out;
        const std::string args = std::string(kSmall) + " --no-png --seed 7 --integrator " + integrator;
        ASSERT_EQ(run_command("CLPPM_LOCAL_SIZE=1 " + clppm_binary() + " -o " + dir + "/a.exr" + args, &out), 0) << out;
        ASSERT_EQ(run_command("CLPPM_LOCAL_SIZE=64 " + clppm_binary() + " -o " + dir + "/b.exr" + args, &out), 0)
            << out;
        ASSERT_EQ(run_clppm("-o " + dir + "/c.exr" + args, &out), 0) << out;
        ASSERT_EQ(run_command("CLPPM_PHOTON_BATCH=777 " + clppm_binary() + " -o " + dir + "/d.exr" + args +
                                  " --stats-json " + dir + "/d.json",
                              &out),
                  0)
            << out;
        Image a = read_exr(dir + "/a.exr"), b = read_exr(dir + "/b.exr"), c = read_exr(dir + "/c.exr"),
              d = read_exr(dir + "/d.exr");
        ASSERT_EQ(a.rgb.size(), b.rgb.size());
        EXPECT_EQ(a.rgb, b.rgb) << integrator;
        EXPECT_EQ(a.rgb, c.rgb) << integrator;
        EXPECT_EQ(a.rgb, d.rgb) << integrator << ": batched photons";
        std::ifstream js(dir + "/d.json");
        std::string json((std::istreambuf_iterator<char>(js)), std::istreambuf_iterator<char>());
        EXPECT_NE(json.find("\"photon_batches_per_pass\": 7"), std::string::npos) << json; // 5000 / 777
    }
}

// CLPPM_OCLGRIND (scripts/check_oclgrind.sh) clears buffers by host writes, writes parts of buffers
// as wholes and keeps every buffer to the end: the same image bit for bit, for every integrator and
// for the sums that several devices merge by writing parts of a buffer.
TEST(Cli, OclgrindModeGivesTheSameImage) {
    const std::vector<std::pair<std::string, std::string>> cases = {{"ppm", ""},
                                                                    {"sppm", ""},
                                                                    {"pppm", ""},
                                                                    {"pt", ""},
                                                                    {"vcm", ""},
                                                                    {"bpt", ""},
                                                                    {"sppm", "POCL_DEVICES='pthread pthread' "},
                                                                    {"vcm", "POCL_DEVICES='pthread pthread' "}};
    for (const auto& [integrator, env] : cases) {
        std::string dir = make_temp_dir("cli"), out;
        std::string args = std::string(kSmall) + " --no-png --seed 5 --integrator " + integrator;
        if (!env.empty()) args += " --device all";
        ASSERT_EQ(run_command(env + "CLPPM_OCLGRIND=1 " + clppm_binary() + " -o " + dir + "/a.exr" + args, &out), 0)
            << out;
        ASSERT_EQ(run_command(env + clppm_binary() + " -o " + dir + "/b.exr" + args, &out), 0) << out;
        Image a = read_exr(dir + "/a.exr"), b = read_exr(dir + "/b.exr");
        ASSERT_FALSE(a.rgb.empty());
        EXPECT_GT(mean_radiance(a), 0.01) << integrator << " " << env;
        EXPECT_EQ(a.rgb, b.rgb) << integrator << " " << env;
    }
}

TEST(Cli, PathTracerRendersToo) {
    std::string dir = make_temp_dir("cli"), out;
    ASSERT_EQ(run_clppm("-o " + dir + "/p.exr --integrator pt" + std::string(kSmall), &out), 0) << out;
    Image img = read_exr(dir + "/p.exr");
    EXPECT_EQ(count_nonfinite(img), 0u);
    EXPECT_GT(mean_radiance(img), 0.01);
}

// Vertex connection and merging and BPT from the command line: an image, the same with any
// work-group size, an error map; what they cannot do is a one-line error naming the option.
TEST(Cli, VcmAndBptRenderAndRefuseWhatTheyCannotDo) {
    std::string dir = make_temp_dir("cli"), out;
    for (const char* integrator : {"vcm", "bpt"}) {
        const std::string args = std::string(kSmall) + " --no-png --integrator " + integrator;
        ASSERT_EQ(run_command("CLPPM_LOCAL_SIZE=1 " + clppm_binary() + " -o " + dir + "/a.exr" + args, &out), 0) << out;
        ASSERT_EQ(run_clppm("-o " + dir + "/b.exr" + args, &out), 0) << out;
        Image a = read_exr(dir + "/a.exr"), b = read_exr(dir + "/b.exr");
        EXPECT_EQ(count_nonfinite(a), 0u) << integrator;
        EXPECT_GT(mean_radiance(a), 0.01) << integrator;
        EXPECT_EQ(a.rgb, b.rgb) << integrator << ": work-group size changed the image";
        EXPECT_EQ(run_clppm("-o " + dir + "/c.exr" + args + " --filter tent", &out), 1) << out;
        EXPECT_NE(out.find("--integrator " + std::string(integrator) + ": light tracing splats with the box filter"),
                  std::string::npos)
            << out;
        EXPECT_EQ(out.find('\n'), out.size() - 1) << "one line: " << out;
        ASSERT_EQ(run_clppm("-o " + dir + "/c.exr" + args + " --error-output " + dir + "/e.exr", &out), 0) << out;
        const Image e = read_exr(dir + "/e.exr");
        EXPECT_EQ(count_nonfinite(e), 0u) << integrator;
        EXPECT_GT(mean_radiance(e), 0.0) << integrator << ": the error map is black";
    }
}

// An aperture wider than the scene images nothing (at the lens's scale floats lose the scene's
// detail: VCM and BPT rendered black and exited 0): every integrator refuses it alike, naming the
// scene's size, before rendering. A wide lens within the scene renders alike in every integrator.
TEST(Cli, ApertureWiderThanTheSceneIsRefusedByEveryIntegrator) {
    const std::string dir = make_temp_dir("aperture");
    std::string out;
    for (const char* integrator : {"ppm", "sppm", "pppm", "pt", "vcm", "bpt"}) {
        EXPECT_EQ(
            run_clppm(std::string(kSmall) + " --integrator " + integrator + " --aperture 1e30 -o " + dir + "/x.exr",
                      &out),
            1)
            << integrator;
        expect_one_line_error(out, "--aperture 1e+30: larger than the scene's bounding diameter 3.4641");
    }
    std::map<std::string, double> mean;
    for (const char* integrator : {"sppm", "pt", "vcm"}) {
        const std::string stats = dir + "/" + integrator + ".json";
        ASSERT_EQ(run_clppm(std::string("--width 32 --height 32 --passes 64 --photons 50000 --quiet --no-png "
                                        "--aperture 0.5 --integrator ") +
                                integrator + " -o " + dir + "/w.exr --stats-json " + stats,
                            &out),
                  0)
            << out;
        mean[integrator] = nlohmann::json::parse(slurp(stats))["mean_radiance"].get<double>();
    }
    EXPECT_NEAR(mean["vcm"] / mean["pt"], 1.0, 0.05);
    EXPECT_NEAR(mean["sppm"] / mean["pt"], 1.0, 0.05);
}

TEST(Cli, ListDevicesShowsTheDevice) {
    std::string out;
    ASSERT_EQ(run_clppm("--list-devices", &out), 0) << out;
    EXPECT_NE(out.find("[0] "), std::string::npos) << out;
    EXPECT_NE(out.find("compute units"), std::string::npos) << out;
    EXPECT_NE(out.find("fp64"), std::string::npos) << out;
    EXPECT_NE(out.find("OpenCL C"), std::string::npos) << out;
}

TEST(Cli, MissingSceneIsAOneLineErrorNamingTheFile) {
    std::string out;
    EXPECT_EQ(run_clppm("/nonexistent/scene.gltf -o " + make_temp_dir("out") + "/x.exr", &out), 1);
    expect_one_line_error(out, "/nonexistent/scene.gltf");
}

// A FIFO (or any path that is not a regular file) as the scene, the environment, a checkpoint to
// resume or an image to compare would block the read for ever: each is refused at once, naming
// the path (under a timeout here, so that a regression fails instead of hanging the suite).
TEST(Cli, PathsThatAreNotRegularFilesAreRefusedAtOnce) {
    const std::string d = make_temp_dir("fifo");
    for (const char* name : {"/s.gltf", "/e.hdr", "/e.exr", "/c.ck", "/a.exr"})
        ASSERT_EQ(mkfifo((d + name).c_str(), 0600), 0) << name;
    const std::string ok = d + "/ok.exr", args = " --width 8 --height 8 --passes 1 --photons 1000 --quiet -o " + ok;
    std::string out;
    ASSERT_EQ(run_clppm(args, &out), 0) << out;
    const std::string cases[][2] = {
        {d + "/s.gltf" + args, d + "/s.gltf"},
        {"--env " + d + "/e.hdr" + args, "--env " + d + "/e.hdr: not a regular file"},
        {"--env " + d + "/e.exr" + args, "--env " + d + "/e.exr: not a regular file"},
        {"--resume " + d + "/c.ck" + args, d + "/c.ck: cannot read checkpoint (not a regular"},
        {"compare " + d + "/a.exr " + ok, "cannot read " + d + "/a.exr: not a regular file"},
        {"compare " + ok + " " + d, "cannot read " + d + ": a folder, not a file"}};
    for (const auto& [args_, message] : cases) {
        EXPECT_EQ(run_command("timeout 60 " + clppm_binary() + " " + args_, &out), 1) << args_ << "\n" << out;
        EXPECT_NE(out.find(message), std::string::npos) << out;
    }
}

TEST(Cli, MalformedGltfIsAOneLineError) {
    std::string out;
    EXPECT_EQ(run_clppm(data("malformed.gltf") + " -o " + make_temp_dir("out") + "/x.exr", &out), 1);
    expect_one_line_error(out, "malformed.gltf");
}

// A scene without lights is lit by the default white environment, and says so in one line; with
// --no-default-light it is refused as before.
TEST(Cli, SceneWithoutLightsGetsTheDefaultEnvironmentOrIsRefused) {
    std::string dir = make_temp_dir("cli"), out;
    EXPECT_EQ(run_clppm(data("embedded.gltf") + " --no-default-light -o " + dir + "/x.exr", &out), 1);
    expect_one_line_error(out, "no lights");
    EXPECT_FALSE(exists(dir + "/x.exr"));
    EXPECT_EQ(run_clppm(data("embedded.gltf") + " --width 8 --height 8 --passes 1 --no-png -o " + dir + "/x.exr", &out),
              0)
        << out;
    EXPECT_NE(out.find("world: the default environment, uniform white of radiance 1 (as a Blender world of strength "
                       "1): " +
                       data("embedded.gltf") +
                       " sets no world of its own and has no lights (--no-default-light "
                       "refuses it)"),
              std::string::npos)
        << out;
    EXPECT_TRUE(exists(dir + "/x.exr"));
}

// A scene with lights of its own and no world is lit by the default environment besides them,
// as a glTF viewer shows it; --no-default-light leaves its own lights alone; a black world in
// the file does the same.
TEST(Cli, ASceneWithLightsGetsTheDefaultEnvironmentToo) {
    const std::string dir = make_temp_dir("cli_world");
    nlohmann::json g = nlohmann::json::parse(slurp(data("lights.gltf")));
    g["scenes"][0].erase("extras"); // the test scene's black world
    std::ofstream(dir + "/lit.gltf") << g.dump();
    auto mean = [&](const std::string& scene, const std::string& args, std::string* out) {
        EXPECT_EQ(run_clppm(scene + " --width 16 --height 16 --passes 4 --integrator pt --no-png " + args + " -o " +
                                dir + "/x.exr",
                            out),
                  0)
            << *out;
        const Image img = read_exr(dir + "/x.exr");
        double sum = 0;
        for (float v : img.rgb) sum += v;
        return sum / double(img.rgb.size());
    };
    std::string out;
    const double with_world = mean(dir + "/lit.gltf", "", &out);
    EXPECT_NE(out.find("world: the default environment"), std::string::npos) << out;
    EXPECT_NE(out.find("sets no world of its own (extras.clppm_environment; --no-default-light: its own lights "
                       "alone)"),
              std::string::npos)
        << out;
    const double own_lights = mean(dir + "/lit.gltf", "--no-default-light", &out);
    EXPECT_NE(out.find("world: none (--no-default-light): the scene's own lights alone"), std::string::npos) << out;
    EXPECT_GT(with_world, own_lights + 0.1);
    EXPECT_EQ(mean(data("lights.gltf"), "", &out), own_lights) << "the black world in the file: the same image";
    EXPECT_NE(out.find("extras.clppm_environment: colour 0,0,0"), std::string::npos) << out;
}

TEST(Cli, UnknownDeviceListsWhatExists) {
    std::string out;
    EXPECT_EQ(run_clppm("--device no-such-device -o " + make_temp_dir("out") + "/x.exr", &out), 1);
    expect_one_line_error(out, "--device no-such-device");
    EXPECT_NE(out.find("[0]"), std::string::npos) << out;
    EXPECT_EQ(run_clppm("--device 99 -o " + make_temp_dir("out") + "/x.exr", &out), 1);
    expect_one_line_error(out, "no device with index 99");
}

TEST(Cli, UnwritableOutputFailsBeforeRendering) {
    std::string out;
    EXPECT_EQ(run_clppm("-o /nonexistent-dir/x.exr --passes 1000000", &out), 1);
    expect_one_line_error(out, "/nonexistent-dir/x.exr");
}

TEST(Cli, BadOptionValuesNameTheOptionAndRange) {
    std::string out;
    EXPECT_EQ(run_clppm("--alpha 1.5", &out), 1);
    expect_one_line_error(out, "--alpha");
    EXPECT_EQ(run_clppm("--bogus", &out), 1);
    expect_one_line_error(out, "--bogus");
    EXPECT_EQ(run_clppm("--camera 3 -o " + make_temp_dir("out") + "/x.exr --passes 1", &out), 1);
    expect_one_line_error(out, "--camera 3");
}

TEST(Cli, KernelBuildFailurePrintsTheBuildLog) {
    std::string dir = make_temp_dir("kernels"), out;
    ASSERT_EQ(run_command("cp " + std::string(CLPPM_SOURCE_DIR) + "/kernels/* " + dir, &out), 0) << out;
    { std::ofstream(dir + "/gather.cl", std::ios::app) << "\nvoid broken(void) { this_is_not_opencl_c = 1; }\n"; }
    EXPECT_EQ(run_clppm("--integrator sppm --kernel-dir " + dir + " -o " + dir + "/x.exr --passes 1", &out), 1);
    EXPECT_NE(out.find("kernel build failed"), std::string::npos) << out;
    EXPECT_NE(out.find("this_is_not_opencl_c"), std::string::npos) << "no build log:\n" << out;
}

// `clppm compare --box K`: a checkerboard of 0.5 and 1.5 against a flat 1 has pixel relative MSE
// 0.25 / 1.01 but none box-filtered over 2 x 2 (each block averages to 1); a bad K is refused.
TEST(Cli, CompareBoxFilteredRelativeMse) {
    const std::string d = make_temp_dir("compare");
    Image a, b;
    a.width = b.width = 8, a.height = b.height = 8;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            a.rgb.insert(a.rgb.end(), 3, (x + y) % 2 ? 1.5f : 0.5f);
            b.rgb.insert(b.rgb.end(), 3, 1.f);
        }
    write_exr(d + "/a.exr", a);
    write_exr(d + "/b.exr", b);
    std::string out;
    ASSERT_EQ(run_clppm("compare " + d + "/a.exr " + d + "/b.exr --box 2", &out), 0) << out;
    const nlohmann::json j = nlohmann::json::parse(out.substr(out.find('{')));
    EXPECT_NEAR(j["rel_mse"].get<double>(), 0.25 / 1.01, 1e-6);
    EXPECT_NEAR(j["box_rel_mse"].get<double>(), 0.0, 1e-12);
    EXPECT_EQ(j["box"].get<int>(), 2);
    // Every pixel is 50% off in luminance: the 90th percentile of the relative error is 0.5.
    EXPECT_NEAR(j["p90_rel_error"].get<double>(), 0.5, 1e-6);
    EXPECT_EQ(run_clppm("compare " + d + "/a.exr " + d + "/b.exr --box 0", &out), 1);
    expect_one_line_error(out, "--box 0: must be an integer in 1..1024");
    // The difference image is a PNG, so its name must say so (it was written into d.jpg).
    EXPECT_EQ(run_clppm("compare " + d + "/a.exr " + d + "/b.exr --diff " + d + "/d.jpg", &out), 1);
    expect_one_line_error(out, "--diff " + d + "/d.jpg: must be a file name ending in .png");
    EXPECT_FALSE(std::ifstream(d + "/d.jpg").good());
    ASSERT_EQ(run_clppm("compare " + d + "/a.exr " + d + "/b.exr --diff " + d + "/d.PNG", &out), 0) << out;
    EXPECT_TRUE(std::ifstream(d + "/d.PNG").good());
}

// clppm --help names the compare command, and clppm compare --help explains it (it was an error).
TEST(Cli, CompareHasHelpAndTheMainHelpNamesIt) {
    std::string out;
    ASSERT_EQ(run_clppm("--help", &out), 0) << out;
    EXPECT_NE(out.find("clppm compare IMAGE.exr REFERENCE.exr"), std::string::npos) << out;
    EXPECT_NE(out.find("CLPPM_CACHE_DIR"), std::string::npos) << out; // the environment variables
    for (const char* help : {"compare --help", "compare -h"}) {
        ASSERT_EQ(run_clppm(help, &out), 0) << out;
        EXPECT_NE(out.find("Usage: clppm compare IMAGE.exr REFERENCE.exr"), std::string::npos) << out;
        EXPECT_NE(out.find("--box K"), std::string::npos) << out;
    }
}
