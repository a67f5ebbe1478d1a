// The path tracer runs short passes several to a launch (integrators/pt_integrator.h,
// kernels/path_trace.cl): the image is the same bit for bit as with one launch a pass, with every
// sampler; a batch never runs past the pass limit nor over a pass that --progressive-output or
// --checkpoint-every counts; and error estimation, whose statistics take each pass apart, keeps
// one pass a launch.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "io/image_io.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

struct Rendered {
    Image image;
    nlohmann::json stats;
};

// tests/data/lights.gltf through the path tracer at 16x16 (passes of well under a millisecond,
// which the integrator batches), with `args`.
Rendered render(const std::string& args, const std::string& env = "") {
    const std::string d = make_temp_dir("batch");
    std::string out;
    const std::string a = env + " " + clppm_binary() + " " + std::string(CLPPM_TEST_DATA) +
                          "/lights.gltf --width 16 --height 16 --integrator pt " + "--quiet --no-png -o " + d +
                          "/i.exr --stats-json " + d + "/s.json " + args;
    EXPECT_EQ(run_command(a, &out), 0) << out;
    return {read_exr(d + "/i.exr"), nlohmann::json::parse(slurp(d + "/s.json"))};
}

} // namespace

// --progressive-output 1 observes every pass, so each pass is a launch of its own, as under
// CLPPM_PASS_BATCH=1: the batched render must equal both bit for bit, with each sampler.
TEST(PassBatching, BatchedPassesGiveTheImageOfOneLaunchAPass) {
    for (const char* sampler : {"sobol", "independent", "zsobol"}) {
        const std::string a = std::string("--passes 300 --sampler ") + sampler;
        const Rendered batched = render(a), single = render(a + " --progressive-output 1");
        const Rendered capped = render(a, "CLPPM_PASS_BATCH=1");
        EXPECT_EQ(capped.stats["pass_launches"], 300) << sampler;
        EXPECT_EQ(batched.image.rgb, capped.image.rgb) << sampler;
        EXPECT_EQ(batched.stats["passes"], 300) << sampler;
        EXPECT_EQ(single.stats["passes"], 300) << sampler;
        EXPECT_EQ(single.stats["pass_launches"], 300) << sampler;
        EXPECT_LT(batched.stats["pass_launches"].get<int>(), 100) << sampler << ": short passes were not batched";
        EXPECT_EQ(batched.image.rgb, single.image.rgb) << sampler;
    }
}

// A batch ends at the pass limit and at each pass --progressive-output counts: with K = 10 and 37
// passes, every launch ends at or before a multiple of 10, so there are at least four.
TEST(PassBatching, BatchesStopWhereTheRenderMustLook) {
    const Rendered r = render("--passes 37 --progressive-output 10");
    EXPECT_EQ(r.stats["passes"], 37);
    EXPECT_GE(r.stats["pass_launches"].get<int>(), 4);
    EXPECT_LT(r.stats["pass_launches"].get<int>(), 37);
    EXPECT_EQ(r.image.rgb, render("--passes 37").image.rgb);
}

// Error estimation takes each pass's samples apart: one pass a launch.
TEST(PassBatching, ErrorEstimationKeepsOnePassALaunch) {
    const Rendered r = render("--passes 40 --target-error 0.0001");
    EXPECT_EQ(r.stats["passes"], 40);
    EXPECT_EQ(r.stats["pass_launches"], 40);
}
