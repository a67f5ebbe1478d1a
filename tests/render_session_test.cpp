// What a render says and leaves behind (src/cli/render_session.cpp): warnings reach stderr even
// with --quiet, an interrupt before the first pass replaces no earlier image, and the EXR header
// records how the image came to be.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "io/output_lock.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

const std::string kArgs = " --width 24 --height 24 --photons 4000 --no-png";

} // namespace

// --quiet silences the progress display, never what the user must know about the result.
TEST(RenderSession, QuietStillShowsWarnings) {
    std::string d = make_temp_dir("quiet"), out;
    // lights.gltf gives its point light a range, which clppm ignores with a warning.
    ASSERT_EQ(
        run_clppm(std::string(CLPPM_TEST_DATA) + "/lights.gltf" + kArgs + " --quiet --passes 1 -o " + d + "/q.exr",
                  &out),
        0)
        << out;
    EXPECT_NE(out.find("clppm: warning:"), std::string::npos) << out;
    EXPECT_NE(out.find("range is ignored"), std::string::npos) << out;
    EXPECT_EQ(out.find("device ["), std::string::npos) << "--quiet must hide the progress notes: " << out;
    EXPECT_EQ(out.find("wrote "), std::string::npos) << out;
}

// Ctrl-C while the kernels build (no cache anywhere: the build takes seconds) stops the render
// before its first pass: the image, stats and checkpoint at the output paths stay as they were.
TEST(RenderSession, InterruptBeforeTheFirstPassReplacesNothing) {
    std::string d = make_temp_dir("early_interrupt"), out;
    const std::string before = "an earlier render's image";
    for (const char* name : {"/i.exr", "/s.json"}) std::ofstream(d + name) << before;
    // PoCL builds an uncached program in <cache>/uncached and removes that folder afterwards, so
    // this render gets a cache folder of its own: one shared with a concurrent test can vanish
    // under it mid-build ("unable to rename temporary ... No such file or directory").
    const std::string run = "CLPPM_NO_CACHE=1 POCL_KERNEL_CACHE=0 POCL_CACHE_DIR=" + d + "/pocl " + clppm_binary() +
                            kArgs + " --quiet --passes 5 -o " + d + "/i.exr --stats-json " + d +
                            "/s.json --checkpoint " + d + "/c.ck";
    const std::string script = run + " & pid=$!; sleep 0.5; kill -INT $pid; wait $pid; echo \"status=$?\"";
    ASSERT_EQ(run_command("bash -c '" + script + "'", &out), 0) << out;
    EXPECT_NE(out.find("status=130"), std::string::npos) << out;
    EXPECT_NE(out.find("interrupted before the first pass: nothing written"), std::string::npos) << out;
    EXPECT_EQ(slurp(d + "/i.exr"), before);
    EXPECT_EQ(slurp(d + "/s.json"), before);
    EXPECT_FALSE(std::ifstream(d + "/c.ck").good()) << "no checkpoint of zero passes";
}

TEST(RenderSession, ExrHeaderRecordsPassesIntegratorAndInterruption) {
    std::string d = make_temp_dir("attributes"), out;
    ASSERT_EQ(run_clppm(kArgs + " --quiet --integrator sppm --passes 3 -o " + d + "/a.exr", &out), 0) << out;
    Image img = read_exr(d + "/a.exr");
    EXPECT_EQ(img.attributes["clppm:passes"], "3");
    EXPECT_EQ(img.attributes["clppm:integrator"], "sppm");
    EXPECT_EQ(img.attributes["clppm:interrupted"], "no");
    EXPECT_FALSE(img.attributes["clppm:version"].empty());
    EXPECT_EQ(img.attributes.count("clppm:png_tonemap"), 0u); // --no-png: nothing to say
    // With a PNG: the tone curve and exposure it applied (the default is aces at 0 stops).
    const std::string png_args = " --width 24 --height 24 --photons 4000 --quiet --passes 1";
    ASSERT_EQ(run_clppm(png_args + " -o " + d + "/b.exr", &out), 0) << out;
    img = read_exr(d + "/b.exr");
    EXPECT_EQ(img.attributes["clppm:png_tonemap"], "aces");
    EXPECT_EQ(img.attributes["clppm:png_exposure_ev"], "0");
    ASSERT_EQ(run_clppm(png_args + " --tonemap Reinhard --exposure -1.5 -o " + d + "/c.exr", &out), 0) << out;
    img = read_exr(d + "/c.exr");
    EXPECT_EQ(img.attributes["clppm:png_tonemap"], "reinhard");
    EXPECT_EQ(img.attributes["clppm:png_exposure_ev"], "-1.5");
}

// A radius beyond the scene would gather every photon everywhere (and an infinite one used to
// hang the gather): refused before rendering, naming the scene's size.
TEST(RenderSession, RadiusBeyondTheSceneIsRefused) {
    std::string d = make_temp_dir("radius"), out;
    for (const char* r : {"1e20", "1e300", "100"}) {
        EXPECT_EQ(run_clppm(kArgs + " --quiet --passes 1 --radius " + r + " -o " + d + "/r.exr", &out), 1) << r;
        EXPECT_NE(out.find("larger than the scene's bounding diameter"), std::string::npos) << out;
    }
    EXPECT_EQ(run_clppm(kArgs + " --quiet --passes 1 --radius 0.05 -o " + d + "/r.exr", &out), 0) << out;
}

// A scene too small (or too large) for float areas renders black or overflows: refused with its
// scale instead. The default scene under a root node scaled by 1e-19, and by 1e-7 (renders).
TEST(RenderSession, SceneOutsideTheFloatRangeIsRefusedNamingItsScale) {
    std::string d = make_temp_dir("scale"), out;
    const nlohmann::json box = nlohmann::json::parse(slurp(std::string(CLPPM_SCENES_DIR) + "/cornell_box.gltf"));
    for (const char* scale : {"1e-19", "1e-7"}) {
        // A new root node, scaled, whose children are the scene's roots (the camera included).
        nlohmann::json gltf = box;
        nlohmann::json& scene = gltf["scenes"][gltf.value("scene", 0)];
        const double k = std::stod(scale);
        gltf["nodes"].push_back({{"scale", {k, k, k}}, {"children", scene["nodes"]}});
        scene["nodes"] = {gltf["nodes"].size() - 1};
        const std::string text = gltf.dump();
        std::ofstream(d + "/s.gltf") << text;
        const int status = run_clppm(d + "/s.gltf" + kArgs + " --quiet --passes 1 -o " + d + "/s.exr", &out);
        if (std::string(scale) == "1e-19") {
            EXPECT_EQ(status, 1) << out;
            EXPECT_NE(out.find("bounding sphere has radius 1.73e-19"), std::string::npos) << out;
        } else {
            EXPECT_EQ(status, 0) << out;
        }
    }
}

// Ctrl-C in the middle of a long pass (a billion photons: minutes) is answered at the next photon
// batch, not at the end of the pass; the render keeps the last complete pass (here none, so it
// writes nothing) and exits 130. `timeout` only guards against a hang.
TEST(RenderSession, InterruptInALongPassStopsAtTheNextBatch) {
    std::string d = make_temp_dir("long_pass"), out;
    const int guard = int(60 * time_scale());
    const std::string run =
        "timeout " + std::to_string(guard) + " " + clppm_binary() +
        " --integrator sppm --width 16 --height 16 --quiet --no-png --photons 1000000000 --passes 2 -o " + d + "/l.exr";
    const std::string script = run + " & pid=$!; sleep 4; kill -INT $pid; wait $pid; echo \"status=$?\"";
    ASSERT_EQ(run_command("bash -c '" + script + "'", &out), 0) << out;
    EXPECT_NE(out.find("status=130"), std::string::npos) << "stopped by the signal, not by the guard: " << out;
    // 130 within seconds of a pass that takes minutes: the signal stopped it (the guard gives 124).
}

namespace {

// The default scene as JSON, for tests that change one thing in it.
nlohmann::json default_scene() {
    return nlohmann::json::parse(slurp(std::string(CLPPM_SCENES_DIR) + "/cornell_box.gltf"));
}

nlohmann::json& material(nlohmann::json& gltf, const std::string& name) {
    for (nlohmann::json& m : gltf["materials"])
        if (m.value("name", "") == name) return m;
    throw std::runtime_error("no material " + name);
}

// A KHR_lights_punctual point light of `intensity` candela in the middle of the box.
void add_point_light(nlohmann::json& gltf, double intensity) {
    gltf["extensionsUsed"].push_back("KHR_lights_punctual");
    gltf["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", intensity}}};
    gltf["nodes"].push_back(
        {{"translation", {0.0, 0.5, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    gltf["scenes"][gltf.value("scene", 0)]["nodes"].push_back(gltf["nodes"].size() - 1);
}

} // namespace

// Every light that ends up emitting nothing is named with the reason, instead of a bare "no
// lights": here a negative emission (warned at load) and a point light of zero intensity.
TEST(RenderSession, DroppedLightsAreNamedWithTheirReason) {
    std::string d = make_temp_dir("dropped"), out;
    nlohmann::json gltf = default_scene();
    material(gltf, "light")["emissiveFactor"] = {-1.0, -1.0, -1.0};
    add_point_light(gltf, 0.0);
    std::ofstream(d + "/s.gltf") << gltf.dump();
    EXPECT_EQ(run_clppm(d + "/s.gltf" + kArgs + " --quiet --no-default-light --passes 1 -o " + d + "/s.exr", &out), 1)
        << out;
    EXPECT_NE(out.find("emissiveFactor * emissiveStrength is negative"), std::string::npos) << out;
    EXPECT_NE(out.find("no lights"), std::string::npos) << out;
    EXPECT_NE(out.find("dropped: point light 0 emits nothing (zero intensity or a closed cone)"), std::string::npos)
        << out;
}

// Messages stay short and readable: a power beyond a float in %g (not 39 digits), a data URI's
// payload as its length (not 70,000 characters of base64).
TEST(RenderSession, MessagesAreShortWhateverTheInput) {
    std::string d = make_temp_dir("messages"), out;
    nlohmann::json gltf = default_scene();
    // Each light fits a float; their total (about 4.9e38 W) does not.
    material(gltf, "light")["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 3e38;
    add_point_light(gltf, 2e37);
    std::ofstream(d + "/bright.gltf") << gltf.dump();
    EXPECT_EQ(run_clppm(d + "/bright.gltf" + kArgs + " --quiet --passes 1 -o " + d + "/s.exr", &out), 1) << out;
    EXPECT_NE(out.find("total power (4."), std::string::npos) << out;
    EXPECT_NE(out.find("e+38 W) does not fit a float"), std::string::npos) << out;
    EXPECT_EQ(out.find("0000000000"), std::string::npos) << "a power printed with %f: " << out;

    gltf = default_scene();
    gltf["buffers"][0]["byteLength"] = 4000000000u;
    std::ofstream(d + "/claim.gltf") << gltf.dump();
    EXPECT_EQ(run_clppm(d + "/claim.gltf" + kArgs + " --quiet --passes 1 -o " + d + "/s.exr", &out), 1) << out;
    EXPECT_NE(out.find("characters>"), std::string::npos) << out;
    EXPECT_LT(out.size(), 400u) << out;
}

// With PoCL, a HOME where no cache directory can be made leaves the device list empty: the
// message names that cause instead of suggesting a missing ICD.
TEST(RenderSession, AnEmptyDeviceListNamesAnUnwritableCache) {
    if (test_device().platform_name.find("Portable Computing Language") == std::string::npos &&
        test_device().platform_name.find("PoCL") == std::string::npos)
        GTEST_SKIP() << "only PoCL needs a writable cache to list its devices";
    std::string d = make_temp_dir("home"), out;
    std::ofstream(d + "/not_a_directory") << "x";
    EXPECT_EQ(run_command("env -u XDG_CACHE_HOME -u POCL_CACHE_DIR HOME=" + d + "/not_a_directory " + clppm_binary() +
                              kArgs + " --passes 1 -o " + d + "/s.exr",
                          &out),
              1)
        << out;
    EXPECT_NE(out.find("PoCL cannot create its kernel cache in " + d + "/not_a_directory/.cache/pocl"),
              std::string::npos)
        << out;
}

// PoCL keeps built programs itself: clppm then caches none (fetching a binary from PoCL compiles
// every kernel once more) and says whose cache served. With PoCL's cache off, clppm's own serves
// the second render.
TEST(RenderSession, ProgramsAreCachedOnceByTheDriverOrByClppm) {
    const bool pocl = test_device().platform_name.find("Portable Computing Language") != std::string::npos ||
                      test_device().platform_name.find("PoCL") != std::string::npos;
    std::string d = make_temp_dir("program_cache"), out;
    auto render = [&](const std::string& env, const char* name) {
        const std::string stats = d + "/" + name + ".json";
        EXPECT_EQ(run_command(env + " CLPPM_CACHE_DIR=" + d + "/clppm_cache " + clppm_binary() + kArgs +
                                  " --quiet --passes 1 -o " + d + "/" + name + ".exr --stats-json " + stats,
                              &out),
                  0)
            << out;
        std::ifstream f(stats);
        return nlohmann::json::parse(f)["kernel_build"];
    };
    auto cached_files = [&]() {
        std::string listing;
        run_command("(ls " + d + "/clppm_cache 2>/dev/null)", &listing);
        return listing;
    };
    const std::string own_pocl = "POCL_CACHE_DIR=" + d + "/pocl";
    nlohmann::json first = render(own_pocl, "a"), second = render(own_pocl, "b");
    EXPECT_EQ(first["driver_cache"], pocl);
    EXPECT_FALSE(first["from_cache"]);
    if (pocl) {
        EXPECT_EQ(cached_files(), "") << "PoCL's cache serves; clppm's stays empty";
        EXPECT_FALSE(second["from_cache"]);
        EXPECT_TRUE(second["driver_cache"]);
        // Without PoCL's cache clppm keeps the program, and the next render loads it.
        const std::string no_pocl = "POCL_KERNEL_CACHE=0 POCL_CACHE_DIR=" + d + "/pocl_off";
        nlohmann::json third = render(no_pocl, "c"), fourth = render(no_pocl, "d");
        EXPECT_FALSE(third["driver_cache"]);
        EXPECT_FALSE(third["from_cache"]);
        EXPECT_NE(cached_files().find(".bin"), std::string::npos) << cached_files();
        EXPECT_TRUE(fourth["from_cache"]);
    } else {
        EXPECT_TRUE(second["from_cache"]);
    }
}

// Two renders given the same output: the second is refused at once, naming the file and the
// first render's pid, and the first finishes undisturbed; the lock goes with the first.
TEST(RenderSession, ASecondRenderToTheSameOutputsIsRefused) {
    std::string d = make_temp_dir("lock"), out;
    const std::string first = clppm_binary() + kArgs + " --quiet --passes 1000000 --progressive-output 1 -o " + d +
                              "/same.exr --checkpoint " + d + "/c.ck";
    const std::string second =
        clppm_binary() + kArgs + " --quiet --passes 1 -o " + d + "/other.exr --checkpoint " + d + "/c.ck";
    const std::string script = first + " & pid=$!; for i in $(seq 1 600); do [ -f " + d +
                               "/same.exr ] && break; sleep 0.05; done; " + second +
                               "; echo \"second=$?\"; kill -INT $pid; wait $pid; echo \"first=$?\"";
    ASSERT_EQ(run_command("bash -c '" + script + "'", &out), 0) << out;
    EXPECT_NE(out.find("second=1"), std::string::npos) << out;
    EXPECT_NE(out.find("c.ck is being written by another clppm render (pid "), std::string::npos) << out;
    EXPECT_NE(out.find("first=130"), std::string::npos) << out;
    EXPECT_FALSE(std::ifstream(d + "/other.exr").good()) << "the refused render wrote nothing";
    EXPECT_FALSE(std::ifstream(OutputLock::lock_path(d + "/same.exr")).good()) << "lock files go with the render";
    // Once the first has gone, the same outputs are free again.
    EXPECT_EQ(run_clppm(kArgs + " --quiet --passes 1 -o " + d + "/same.exr --checkpoint " + d + "/c.ck", &out), 0)
        << out;
}
