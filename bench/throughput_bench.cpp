// Throughput: passes and photons per second of every integrator on the shipped scenes with the
// device time of each phase, specialised against generic kernels, kernel build time cold and
// cached, time to first image, and how the cost of a pass grows with photons per pass, resolution
// and triangle count. Writes throughput.json and throughput.md into --out.
//
//   throughput_bench [--quick] [--device SPEC] [--out DIR] [--seconds S]
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "bench_util.h"
#include "io/stats_json.h"

using namespace clppm;
using namespace clppm::bench;

namespace {

using Args = BenchOptions;

struct Measure {
    double passes_per_s = 0, photons_per_s = 0, seconds_per_pass = 0;
    std::map<std::string, double> phase_per_pass; // device seconds per pass
    double build_s = 0;
};

// Renders one warm-up pass, then passes for `seconds` (at least two), and reports rates.
Measure measure(const DeviceInfo& dev, const std::string& scene, const RenderSettings& s, double seconds,
                bool generic = false) {
    Render r(dev, scene, s, generic);
    r.integ->run_pass();
    const IntegratorStats before = r.integ->stats();
    const double t0 = now_s();
    uint64_t passes = 0;
    while (passes < 2 || now_s() - t0 < seconds) {
        r.integ->run_pass();
        ++passes;
    }
    const double dt = now_s() - t0;
    const IntegratorStats& st = r.integ->stats();
    Measure m;
    m.passes_per_s = passes / dt;
    m.seconds_per_pass = dt / passes;
    m.photons_per_s = double(st.photons_emitted - before.photons_emitted) / dt;
    for (const auto& [k, v] : st.phase_seconds) {
        auto it = before.phase_seconds.find(k);
        m.phase_per_pass[k] = (v - (it == before.phase_seconds.end() ? 0.0 : it->second)) / passes;
    }
    m.build_s = r.build.seconds;
    return m;
}

// Build time and time to first image of the clppm binary with empty caches, then with warm ones.
Json build_times(const std::string& dir, bool quick) {
    Json out = Json::array();
    const std::string cache = dir + "/kernel_cache";
    std::string cmd_base = "rm -rf " + cache + " && mkdir -p " + cache;
    if (std::system(cmd_base.c_str()) != 0) return out;
    for (const char* integ : {"ppm", "sppm", "pt"}) {
        for (const char* phase : {"cold", "cached"}) {
            const std::string stats = dir + "/build_" + integ + "_" + phase + ".json";
            const std::string cmd = "CLPPM_CACHE_DIR=" + cache + " POCL_CACHE_DIR=" + cache + " " + CLPPM_BINARY +
                                    " --width 64 --height 64 --passes 1 --photons 10000 --quiet --no-png -o " + dir +
                                    "/build.exr --integrator " + integ + " --stats-json " + stats;
            if (std::system(cmd.c_str()) != 0) continue;
            std::ifstream f(stats);
            Json j = Json::parse(f);
            out.push_back({{"integrator", integ},
                           {"cache", phase},
                           {"build_seconds", j["kernel_build"]["seconds"]},
                           {"first_image_seconds", j["total_seconds"]}});
        }
        if (quick) break;
    }
    return out;
}

} // namespace

int main(int argc, char** argv) try {
    Args a;
    CLI::App app{"throughput_bench: passes and photons per second, device time per phase, build times"};
    add_bench_options(app, a, "A smoke run: one small scene, short", "Where throughput.json goes",
                      "Seconds per measurement");
    CLI11_PARSE(app, argc, argv);
    if (a.quick) a.seconds = 0.2;
    const DeviceInfo& dev = bench_device(a.device);
    const unsigned size = a.quick ? 32 : 256;
    const uint64_t photons = a.quick ? 5000 : 200000;
    std::vector<std::string> scenes = a.quick
                                          ? std::vector<std::string>{"cornell_box"}
                                          : std::vector<std::string>{"cornell_box", "caustic", "bunny_100k", "furnace"};
    Json j;
    j["device"] = dev.name + " (" + dev.platform_name + ", " + dev.driver_version + ")";
    j["size"] = size;
    j["photons_per_pass"] = photons;
    std::ostringstream md;
    md << "Device: " << dev.name << " (" << dev.platform_name << ", driver " << dev.driver_version << ")\n\n";

    // 1. Every integrator on every scene, with phases; specialised vs generic (PPM, SPPM).
    md << "### Passes per second, " << size << "x" << size << ", " << photons << " photons per pass\n\n"
       << "| scene | integrator | passes/s | Mphotons/s | generic passes/s | specialised/generic | device ms per pass "
          "by phase |\n"
       << "|---|---|---|---|---|---|---|\n";
    Json rows = Json::array();
    for (const std::string& scene : scenes) {
        for (std::string integ : {"ppm", "sppm", "pppm", "pt"}) {
            RenderSettings s = square_settings(integ, size, photons);
            Measure m = measure(dev, scene, s, a.seconds);
            Measure g;
            const bool compare_generic = integ == "ppm" || integ == "sppm";
            if (compare_generic) g = measure(dev, scene, s, a.seconds, true);
            std::string phases;
            Json jp = Json::object();
            for (const auto& [k, v] : m.phase_per_pass) {
                phases += k + " " + fmt("%.1f", v * 1e3) + ", ";
                jp[k] = v;
            }
            if (!phases.empty()) phases.resize(phases.size() - 2);
            md << "| " << scene << " | " << integ << " | " << fmt("%.2f", m.passes_per_s) << " | "
               << (integ == "pt" ? std::string("-") : fmt("%.2f", m.photons_per_s * 1e-6)) << " | "
               << (compare_generic ? fmt("%.2f", g.passes_per_s) : std::string("-")) << " | "
               << (compare_generic ? fmt("%.2f", m.passes_per_s / g.passes_per_s) : std::string("-")) << " | " << phases
               << " |\n";
            rows.push_back({{"scene", scene},
                            {"integrator", integ},
                            {"passes_per_second", m.passes_per_s},
                            {"photons_per_second", m.photons_per_s},
                            {"generic_passes_per_second", compare_generic ? g.passes_per_s : 0.0},
                            {"phase_seconds_per_pass", jp}});
            std::cerr << scene << " " << integ << ": " << m.passes_per_s << " passes/s\n";
        }
    }
    j["integrators"] = rows;

    // 2. Scaling of one SPPM pass: photons per pass, resolution, triangles.
    Json scaling = Json::array();
    auto scale_row = [&](const std::string& what, const std::string& scene, unsigned sz, uint64_t ph) {
        Measure m = measure(dev, scene, square_settings("sppm", sz, ph), a.seconds);
        scaling.push_back({{"vary", what},
                           {"scene", scene},
                           {"size", sz},
                           {"photons", ph},
                           {"seconds_per_pass", m.seconds_per_pass},
                           {"photons_per_second", m.photons_per_s}});
        md << "| " << what << " | " << scene << " | " << sz << "x" << sz << " | " << ph << " | "
           << fmt("%.4f", m.seconds_per_pass) << " | " << fmt("%.2f", m.photons_per_s * 1e-6) << " |\n";
        std::cerr << what << " " << scene << " " << sz << " " << ph << ": " << m.seconds_per_pass << " s/pass\n";
    };
    md << "\n### How a pass's cost grows (SPPM)\n\n| varied | scene | size | photons | s/pass | Mphotons/s "
          "|\n|---|---|---|---|---|---|\n";
    for (uint64_t ph : a.quick ? std::vector<uint64_t>{5000, 10000}
                               : std::vector<uint64_t>{10000, 30000, 100000, 300000, 1000000, 3000000, 10000000})
        scale_row("photons", "cornell_box", a.quick ? 32 : 128, ph);
    for (unsigned sz : a.quick ? std::vector<unsigned>{16, 32} : std::vector<unsigned>{64, 128, 256, 512, 1024})
        scale_row("pixels", "cornell_box", sz, a.quick ? 5000 : 100000);
    if (!a.quick)
        for (const char* scene : {"plane_point_light", "furnace", "cornell_box", "bunny_100k"})
            scale_row("triangles", scene, 128, 100000);
    j["scaling"] = scaling;

    // 3. Kernel builds and the first image, through the clppm binary with fresh caches.
    Json builds = build_times(a.out, a.quick);
    j["builds"] = builds;
    md << "\n### Kernel build and time to first image (64x64, one pass)\n\n| integrator | caches | build s | first "
          "image s |\n|---|---|---|---|\n";
    for (const Json& b : builds)
        md << "| " << b["integrator"].get<std::string>() << " | " << b["cache"].get<std::string>() << " | "
           << fmt("%.3f", b["build_seconds"].get<double>()) << " | "
           << fmt("%.3f", b["first_image_seconds"].get<double>()) << " |\n";

    write_stats_json(a.out + "/throughput.json", j);
    write_file_atomic(a.out + "/throughput.md", md.str());
    std::cout << md.str();
    return 0;
} catch (const std::exception& e) {
    std::cerr << "throughput_bench: error: " << e.what() << "\n";
    return 1;
}
