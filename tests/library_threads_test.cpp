// The library from several threads at once (issue 61): eight renders in one process, every
// integrator, each with its own RenderJob and RenderLoop as the Python module makes them, give
// each the image it gives alone, bit for bit; and a render's own cancel stops it and no other.
// scripts/test_tsan.sh runs this test under ThreadSanitizer as well.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "render/option_table.h"
#include "render/render_job.h"
#include "render/render_loop.h"
#include "test_util.h"
#include "util/cancellation.h"

using namespace clppm;
using namespace clppm::test;

namespace {

struct Job {
    const char* integrator;
    uint64_t seed;
};

const Job kJobs[] = {{"sppm", 1}, {"pt", 2}, {"vcm", 3}, {"ppm", 4}, {"bpt", 5}, {"pppm", 6}, {"pt", 7}, {"sppm", 8}};

RenderOptions options_for(const Job& job) {
    RenderOptions o;
    for (const auto& [name, value] :
         std::vector<std::pair<std::string, std::string>>{{"--integrator", job.integrator},
                                                          {"--seed", std::to_string(job.seed)},
                                                          {"--width", "16"},
                                                          {"--height", "12"},
                                                          {"--passes", "3"},
                                                          {"--photons", "3000"},
                                                          {"--device", std::to_string(test_device().index)}})
        apply_render_option(o, *find_render_option(name), name, value);
    o.quiet = true;
    check_render_options(o);
    return o;
}

std::vector<float> render(const Job& job) {
    RenderLog log(true);
    RenderJob r(options_for(job), log);
    RenderLoop loop(r, {});
    while (loop.step()) {}
    return r.image().rgb;
}

} // namespace

TEST(LibraryThreads, EightRendersAtOnceGiveTheImagesEachGivesAlone) {
    std::vector<std::vector<float>> alone, together(std::size(kJobs));
    for (const Job& job : kJobs) alone.push_back(render(job));
    std::vector<std::string> errors(std::size(kJobs));
    std::vector<std::thread> threads;
    for (size_t k = 0; k < std::size(kJobs); ++k)
        threads.emplace_back([&, k] {
            try {
                together[k] = render(kJobs[k]);
            } catch (const std::exception& e) {
                errors[k] = e.what();
            }
        });
    for (std::thread& t : threads) t.join();
    for (size_t k = 0; k < std::size(kJobs); ++k) {
        EXPECT_EQ(errors[k], "") << kJobs[k].integrator;
        ASSERT_FALSE(alone[k].empty());
        EXPECT_EQ(alone[k], together[k]) << kJobs[k].integrator << " (seed " << kJobs[k].seed
                                         << ") differs when rendered beside the others";
    }
}

// One render's token stops its pass; a second render on another thread, with a token of its own
// that nobody raises, runs all its passes.
TEST(LibraryThreads, ATokenStopsItsOwnRenderOnly) {
    CancelToken stop, keep;
    stop.request();
    std::atomic<bool> stopped{false};
    uint64_t passes_kept = 0;
    std::thread a([&] {
        const CancelScope scope(&stop);
        RenderLog log(true);
        RenderJob r(options_for({"sppm", 1}), log);
        RenderLoop loop(r, {});
        stopped = !loop.step();
    });
    std::thread b([&] {
        const CancelScope scope(&keep);
        RenderLog log(true);
        RenderJob r(options_for({"sppm", 2}), log);
        RenderLoop loop(r, {});
        while (loop.step()) {}
        passes_kept = r.passes();
    });
    a.join();
    b.join();
    EXPECT_TRUE(stopped);
    EXPECT_EQ(passes_kept, 3u);
    EXPECT_FALSE(cancel_requested()) << "a render's token leaked into the process's request";
}
