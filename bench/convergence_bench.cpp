// The trade between speed and accuracy: relative error against a reference as wall time grows,
// for the integrators at equal time and for sweeps of alpha, photons per pass and initial radius.
// One render per setting, its image sampled at doubling times. Writes convergence_<scene>.csv and
// convergence_<scene>.md into --out, and log-log plots (PNG) when gnuplot is installed.
//
//   convergence_bench [--quick] [--scene NAME] [--size N] [--seconds S] [--reference-seconds R]
//                     [--device SPEC] [--out DIR]
//
// The reference is a long SPPM render (box pixel filter, 1M photons per pass, its own seed), kept
// in --out as reference_<scene>_<size>.exr and reused while its size matches. Every setting uses
// another seed, so no photon is shared with the reference.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <sys/stat.h>

#include <CLI/CLI.hpp>

#include "bench_util.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "io/stats_json.h"

using namespace clppm;
using namespace clppm::bench;

namespace {

struct Args : BenchOptions {
    std::string scene = "cornell_box";
    unsigned size = 128;
    double reference_seconds = 600;
    Args() { seconds = 32; }
};

struct Setting {
    std::string group, name;
    RenderSettings s;
};

bool exists(const std::string& p) {
    struct stat st;
    return ::stat(p.c_str(), &st) == 0;
}

Image reference_image(const Args& a, const DeviceInfo& dev) {
    const std::string path = a.out + "/reference_" + a.scene + "_" + std::to_string(a.size) + ".exr";
    if (exists(path)) return read_exr(path);
    RenderSettings s;
    s.integrator = "sppm";
    s.width = s.height = a.size;
    s.photons = a.quick ? 50000 : 1000000;
    s.seed = 1000;
    Render r(dev, a.scene, s);
    const double t0 = now_s();
    while (now_s() - t0 < a.reference_seconds) r.integ->run_pass();
    Image img = r.integ->image();
    write_exr(path, img);
    std::cerr << "reference: " << r.integ->stats().passes << " passes, " << r.integ->stats().photons_emitted
              << " photons in " << now_s() - t0 << " s\n";
    return img;
}

} // namespace

int main(int argc, char** argv) try {
    Args a;
    CLI::App app{"convergence_bench: error against time for each integrator's settings"};
    add_bench_options(app, a, "A smoke run: small, short", "Where the results go", "Seconds per setting");
    app.add_option("--scene", a.scene, "cornell_box, caustic, ... or a glTF file");
    app.add_option("--size", a.size, "Image width and height");
    app.add_option("--reference-seconds", a.reference_seconds, "Seconds for the reference");
    CLI11_PARSE(app, argc, argv);
    if (a.quick) a.size = 24, a.seconds = 0.4, a.reference_seconds = 3;
    const DeviceInfo& dev = bench_device(a.device);
    const Image ref = reference_image(a, dev);

    // The heuristic radius of this scene and size, to scale the radius sweep from.
    double r0 = 0;
    {
        RenderSettings s;
        s.integrator = "sppm";
        s.width = s.height = a.size;
        s.photons = 1000;
        Render probe(dev, a.scene, s);
        r0 = probe.integ->stats().initial_radius;
    }
    auto base = [&](const std::string& integ) {
        RenderSettings s;
        s.integrator = integ;
        s.width = s.height = a.size;
        s.photons = a.quick ? 5000 : 200000;
        s.seed = 7;
        return s;
    };
    std::vector<Setting> settings;
    for (std::string integ : {"ppm", "sppm", "pppm", "pt"}) settings.push_back({"integrator", integ, base(integ)});
    for (double alpha : {0.3, 0.5, 0.7, 0.9}) {
        Setting st{"alpha", "alpha " + fmt("%.1f", alpha), base("sppm")};
        st.s.alpha = alpha;
        settings.push_back(st);
    }
    for (uint64_t ph : a.quick ? std::vector<uint64_t>{2000, 20000} : std::vector<uint64_t>{50000, 200000, 1000000}) {
        Setting st{"photons", std::to_string(ph) + " photons", base("sppm")};
        st.s.photons = ph;
        settings.push_back(st);
    }
    for (double f : {0.5, 1.0, 2.0, 4.0}) {
        Setting st{"radius", "radius " + fmt("%.1f", f) + "x", base("sppm")};
        st.s.radius = f * r0;
        settings.push_back(st);
    }
    for (DirectLighting d : {DirectLighting::Sample, DirectLighting::Photons}) {
        Setting st{"direct", std::string("ppm --direct ") + to_string(d), base("ppm")};
        st.s.direct = d;
        st.s.spp = 4; // stratified hit points: PPM then converges to nearly the box-filtered reference
        settings.push_back(st);
    }

    std::ostringstream csv;
    csv << "scene,group,setting,seconds,passes,rel_rmse,rel_mse,mean_ratio\n";
    std::ostringstream md;
    md << "Scene " << a.scene << ", " << a.size << "x" << a.size << ", device " << dev.name
       << "; relative MSE against the reference at each time, mean over pixels of (I - R)^2 / (R^2 + 0.01) (lower is "
          "better)\n\n";
    std::vector<double> times;
    for (double t = a.seconds; t >= a.seconds / 32 - 1e-9; t /= 2) times.insert(times.begin(), t);
    md << "| setting |";
    for (double t : times) md << " " << fmt("%.2f", t) << " s |";
    md << "\n|---|";
    for (size_t k = 0; k < times.size(); ++k) md << "---|";
    md << "\n";
    for (const Setting& st : settings) {
        Render r(dev, a.scene, st.s);
        const double t0 = now_s() - r.prepare_seconds; // the eye pass counts too
        md << "| " << st.group << ": " << st.name << " |";
        for (double t : times) {
            while (now_s() - t0 < t) r.integ->run_pass();
            const double elapsed = now_s() - t0;
            ImageDifference d = compare_images(r.integ->image(), ref);
            csv << a.scene << "," << st.group << "," << st.name << "," << elapsed << "," << r.integ->stats().passes
                << "," << d.rel_rmse << "," << d.rel_mse << "," << (d.mean_b > 0 ? d.mean_a / d.mean_b : 0.0) << "\n";
            md << " " << fmt("%.5f", d.rel_mse) << " |";
        }
        md << "\n";
        std::cerr << st.group << " " << st.name << " done\n";
    }
    const std::string stem = a.out + "/convergence_" + a.scene;
    write_file_atomic(stem + ".csv", csv.str());
    write_file_atomic(stem + ".md", md.str());
    std::cout << md.str();
    // Log-log plots, one per group, when gnuplot is there (optional: the CSV is the result).
    const std::string plot = std::string("command -v gnuplot >/dev/null && gnuplot -e \"csv='") + stem +
                             ".csv'; out='" + stem + "'\" " + CLPPM_SOURCE_DIR + "/bench/convergence.gnuplot";
    if (std::system(plot.c_str()) != 0) std::cerr << "(no plots: gnuplot not installed or failed)\n";
    return 0;
} catch (const std::exception& e) {
    std::cerr << "convergence_bench: error: " << e.what() << "\n";
    return 1;
}
