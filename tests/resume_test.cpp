// Nothing a user rendered is lost: a checkpointed render resumes to the same image bit for bit,
// Ctrl-C and SIGTERM stop cleanly with the images and statistics written, a second Ctrl-C quits at
// once, and a checkpoint that does not belong to this render is refused with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

#include "io/checkpoint.h"
#include "io/image_io.h"
#include "shared_types.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

const std::string kArgs = " --width 24 --height 24 --photons 4000 --quiet --no-png";

} // namespace

TEST(Resume, StoppedAndResumedEqualsNeverStopped) {
    for (const char* integrator : {"ppm", "sppm", "pppm", "pt", "vcm"})
        expect_resume_is_exact(kArgs + " --integrator " + integrator, integrator);
}

TEST(Resume, RefusesACheckpointOfAnotherRenderSayingWhatDiffers) {
    std::string d = make_temp_dir("resume"), out;
    ASSERT_EQ(run_clppm(kArgs + " --passes 1 -o " + d + "/a.exr --checkpoint " + d + "/c.ck", &out), 0) << out;
    EXPECT_EQ(run_clppm(kArgs + " --passes 2 -o " + d + "/b.exr --alpha 0.5 --resume " + d + "/c.ck", &out), 1);
    EXPECT_NE(out.find("--alpha 0.7 in the checkpoint, 0.5 now"), std::string::npos) << out;
    EXPECT_EQ(run_clppm(std::string(CLPPM_SCENES_DIR) + "/furnace.gltf" + kArgs + " --passes 2 -o " + d +
                            "/b.exr --resume " + d + "/c.ck",
                        &out),
              1);
    EXPECT_NE(out.find("scene"), std::string::npos) << out;
    EXPECT_EQ(run_clppm(kArgs + " --passes 2 -o " + d + "/b.exr --seed 9 --resume " + d + "/c.ck", &out), 1);
    EXPECT_NE(out.find("--seed 1 in the checkpoint, 9 now"), std::string::npos) << out;
}

TEST(Resume, DamagedOrForeignCheckpointsAreErrors) {
    std::string d = make_temp_dir("resume"), out;
    ASSERT_EQ(run_clppm(kArgs + " --passes 1 -o " + d + "/a.exr --checkpoint " + d + "/c.ck", &out), 0) << out;
    std::string bytes = slurp(d + "/c.ck");
    bytes[bytes.size() / 2] ^= 0x5a;
    std::ofstream(d + "/damaged.ck", std::ios::binary) << bytes;
    EXPECT_EQ(run_clppm(kArgs + " --passes 2 -o " + d + "/b.exr --resume " + d + "/damaged.ck", &out), 1);
    EXPECT_NE(out.find("damaged.ck: checkpoint is damaged"), std::string::npos) << out;
    std::ofstream(d + "/short.ck", std::ios::binary) << bytes.substr(0, 20);
    EXPECT_EQ(run_clppm(kArgs + " --passes 2 -o " + d + "/b.exr --resume " + d + "/short.ck", &out), 1);
    EXPECT_NE(out.find("short.ck"), std::string::npos) << out;
    EXPECT_EQ(run_clppm(kArgs + " --passes 2 -o " + d + "/b.exr --resume " + d + "/a.exr", &out), 1);
    EXPECT_NE(out.find("a.exr: not a clppm checkpoint"), std::string::npos) << out;
    EXPECT_EQ(run_clppm(kArgs + " --passes 2 -o " + d + "/b.exr --resume " + d + "/missing.ck", &out), 1);
    EXPECT_NE(out.find("missing.ck"), std::string::npos) << out;
}

// Ctrl-C: the pass in flight finishes, the image, statistics and checkpoint are written, the exit
// status is 130; resuming to N passes then equals a render of N passes that was never stopped.
TEST(Resume, InterruptWritesEverythingAndResumesExactly) {
    for (const char* sig : {"INT", "TERM"}) {
        std::string d = make_temp_dir("interrupt"), out;
        const std::string run = clppm_binary() + kArgs + " --passes 1000000 --progressive-output 1 -o " + d +
                                "/i.exr --checkpoint " + d + "/c.ck --stats-json " + d + "/s.json";
        // Wait for the first progressive image, so that the signal lands mid-render.
        const std::string script = run + " & pid=$!; for i in $(seq 1 600); do [ -f " + d +
                                   "/i.exr ] && break; sleep 0.05; done; sleep 0.3; kill -" + sig +
                                   " $pid; wait $pid; echo \"status=$?\"";
        ASSERT_EQ(run_command("bash -c '" + script + "'", &out), 0) << out;
        EXPECT_NE(out.find(std::string("status=") + (std::string(sig) == "INT" ? "130" : "143")), std::string::npos)
            << out;
        Image img = read_exr(d + "/i.exr");
        EXPECT_EQ(count_nonfinite(img), 0u);
        EXPECT_EQ(img.attributes["clppm:interrupted"], "yes") << "the EXR must say it was interrupted";
        std::string stats = slurp(d + "/s.json");
        EXPECT_NE(stats.find("\"interrupted\": true"), std::string::npos) << stats;
        size_t at = stats.find("\"passes\": ");
        ASSERT_NE(at, std::string::npos) << stats;
        const uint64_t passes = std::stoull(stats.substr(at + 10));
        ASSERT_GE(passes, 1u);
        const std::string target = std::to_string(passes + 2);
        ASSERT_EQ(run_clppm(kArgs + " --passes " + target + " -o " + d + "/r.exr --resume " + d + "/c.ck", &out), 0)
            << out;
        ASSERT_EQ(run_clppm(kArgs + " --passes " + target + " -o " + d + "/n.exr", &out), 0) << out;
        EXPECT_EQ(read_exr(d + "/r.exr").rgb, read_exr(d + "/n.exr").rgb) << sig;
    }
}

// --sampler zsobol lays its points out for the planned passes: a checkpoint records the layout
// (2^1 for --passes 2), a resumed render goes on in it (the passes past the plan are a new
// generation, unbiased: the same mean as an unbroken render), and a layout no render plans is
// refused naming the field. Without a pass limit there is no plan: a one-line error.
TEST(Resume, ZsobolGoesOnInItsPlannedLayout) {
    std::string d = make_temp_dir("zsobol"), out;
    const std::string a = kArgs + " --integrator pt --sampler zsobol";
    ASSERT_EQ(run_clppm(a + " --passes 2 -o " + d + "/a.exr --checkpoint " + d + "/c.ck", &out), 0) << out;
    Checkpoint ck = read_checkpoint(d + "/c.ck");
    EXPECT_EQ(ck.header.value("zsobol_log2_passes", -1), 1) << ck.header.dump();
    ASSERT_EQ(run_clppm(a + " --passes 64 -o " + d + "/r.exr --resume " + d + "/c.ck", &out), 0) << out;
    ASSERT_EQ(run_clppm(a + " --passes 64 -o " + d + "/n.exr", &out), 0) << out;
    const Image r = read_exr(d + "/r.exr"), n = read_exr(d + "/n.exr");
    EXPECT_EQ(count_nonfinite(r), 0u);
    EXPECT_NE(r.rgb, n.rgb) << "the resumed render must keep the checkpoint's layout, not plan anew";
    EXPECT_NEAR(mean_radiance(r) / mean_radiance(n), 1.0, 0.03);
    ck.header["zsobol_log2_passes"] = 33;
    write_checkpoint(d + "/bad.ck", ck);
    EXPECT_EQ(run_clppm(a + " --passes 4 -o " + d + "/b.exr --resume " + d + "/bad.ck", &out), 1);
    EXPECT_NE(out.find("zsobol_log2_passes = 33"), std::string::npos) << out;
    EXPECT_EQ(run_clppm(a + " --passes 0 --time 1 -o " + d + "/t.exr", &out), 1);
    EXPECT_NE(out.find("--sampler zsobol: its points are laid out for a planned number of passes"), std::string::npos)
        << out;
}

// A second Ctrl-C quits at once; whatever was written before stays a complete image.
TEST(Resume, SecondInterruptQuitsAtOnceWithoutCorruptingFiles) {
    std::string d = make_temp_dir("interrupt2"), out;
    const std::string run = clppm_binary() + " --width 64 --height 64 --photons 200000 --quiet --no-png" +
                            " --passes 1000000 --progressive-output 1 -o " + d + "/i.exr";
    const std::string script = run + " & pid=$!; for i in $(seq 1 600); do [ -f " + d +
                               "/i.exr ] && break; sleep 0.05; done; kill -INT $pid; kill -INT $pid; wait $pid; "
                               "echo \"status=$?\"";
    ASSERT_EQ(run_command("bash -c '" + script + "'", &out), 0) << out;
    EXPECT_NE(out.find("status=130"), std::string::npos) << out;
    Image img = read_exr(d + "/i.exr");
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(count_nonfinite(img), 0u);
}

// A checkpoint whose checksum is right but whose fields no render can produce is refused, naming
// the field: negative radii would hang the gather, wrong counters would change the image.
TEST(Resume, ImpossibleCheckpointFieldsAreRefusedNamingThem) {
    for (const char* integrator : {"ppm", "sppm", "pt", "vcm"}) {
        std::string d = make_temp_dir("crafted"), out;
        const std::string a = kArgs + " --integrator " + integrator;
        ASSERT_EQ(run_clppm(a + " --passes 2 -o " + d + "/a.exr --checkpoint " + d + "/c.ck", &out), 0) << out;
        const Checkpoint good = read_checkpoint(d + "/c.ck");
        struct Craft {
            const char* field;
            std::function<void(Checkpoint&)> edit;
        };
        std::vector<Craft> crafts = {
            {"passes", [](Checkpoint& c) { c.header["passes"] = -3; }},
            // PT emits none; the photon integrators emit --photons per pass.
            {"photons_emitted",
             [pt = std::string(integrator) == "pt"](Checkpoint& c) { c.header["photons_emitted"] = pt ? 7 : 0; }},
            {"phase_seconds", [](Checkpoint& c) { c.header["phase_seconds"]["gather"] = -1.0; }},
        };
        if (std::string(integrator) == "vcm") { // one light sub-path per pixel and pass; the radius shrinks
            crafts.push_back({"vcm_r2", [](Checkpoint& c) { c.header["vcm_r2"] = -1.0; }});
            crafts.push_back({"initial_radius", [](Checkpoint& c) { c.header["initial_radius"] = 1e30; }});
            crafts.push_back({"accum[", [](Checkpoint& c) {
                                  auto v = c.get<double>("accum", c.blobs["accum"].size() / sizeof(double));
                                  v[2] = std::nan("");
                                  c.put("accum", v);
                              }});
        } else if (std::string(integrator) != "pt") {
            crafts.push_back({"typical_radius", [](Checkpoint& c) { c.header["typical_radius"] = -0.5; }});
            crafts.push_back({"max_radius", [](Checkpoint& c) { c.header["max_radius"] = 1e30; }});
            crafts.push_back({"initial_radius", [](Checkpoint& c) { c.header["initial_radius"] = -1.0; }});
            crafts.push_back({"stats[0]", [](Checkpoint& c) {
                                  auto s =
                                      c.get<dev::HitStats>("stats", c.blobs["stats"].size() / sizeof(dev::HitStats));
                                  s[0].r2 = std::nan("");
                                  c.put("stats", s);
                              }});
        } else {
            crafts.push_back({"accum[", [](Checkpoint& c) {
                                  auto v = c.get<double>("accum", c.blobs["accum"].size() / sizeof(double));
                                  v[1] = -1;
                                  c.put("accum", v);
                              }});
        }
        for (const Craft& craft : crafts) {
            Checkpoint bad = good;
            craft.edit(bad);
            write_checkpoint(d + "/bad.ck", bad);
            EXPECT_EQ(run_clppm(a + " --passes 4 -o " + d + "/b.exr --resume " + d + "/bad.ck", &out), 1)
                << integrator << " " << craft.field << ": " << out;
            EXPECT_NE(out.find(std::string("checkpoint field ") + craft.field), std::string::npos)
                << integrator << ": " << out;
            EXPECT_EQ(out.find('\n'), out.size() - 1) << "one line: " << out;
        }
    }
}
