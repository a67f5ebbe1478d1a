// error_calibration: how well the progressive error estimate (src/integrators/error_estimate.h) predicts the
// actual error. For each benchmark scene it renders a reference (SPPM, another seed,
// --ref-passes passes), then an SPPM render with error estimation, and at a few pass counts
// compares, per pixel and on luminance, the estimated bound with the actual error against the
// reference: the fraction of pixels within their bound (to compare with the confidence), and the
// image-level (90th percentile) estimated and actual relative errors. Writes a CSV and a markdown
// table to --out (FILE.csv and FILE.md). Measures; never fails on a number.
//
//   error_calibration [--out PREFIX] [--size N] [--photons M] [--passes N] [--ref-passes N]
//                     [--confidence P] [--device SPEC] [--quick]
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.h"
#include "integrators/error_estimate.h"

using namespace clppm;
using namespace clppm::bench;

namespace {

struct Args {
    std::string out = "error_calibration", device;
    unsigned size = 48;
    uint64_t photons = 50000, passes = 200, ref_passes = 1600;
    double confidence = 0.95;
};

std::vector<float> luminance(const Image& img) {
    std::vector<float> y(size_t(img.width) * img.height);
    for (size_t i = 0; i < y.size(); ++i)
        y[i] = float(0.2126 * img.rgb[3 * i] + 0.7152 * img.rgb[3 * i + 1] + 0.0722 * img.rgb[3 * i + 2]);
    return y;
}

struct Row {
    std::string scene;
    uint64_t pass;
    double seconds, estimated, actual, coverage, median_ratio;
};

} // namespace

int main(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        std::string k = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (k == "--out") a.out = next();
        else if (k == "--size") a.size = unsigned(std::stoul(next()));
        else if (k == "--photons") a.photons = std::stoull(next());
        else if (k == "--passes") a.passes = std::stoull(next());
        else if (k == "--ref-passes") a.ref_passes = std::stoull(next());
        else if (k == "--confidence") a.confidence = std::stod(next());
        else if (k == "--device") a.device = next();
        else if (k == "--quick") a.size = 16, a.photons = 5000, a.passes = 8, a.ref_passes = 32;
        else {
            std::fprintf(stderr, "error_calibration: unknown argument %s\n", k.c_str());
            return 1;
        }
    }
    try {
        const DeviceInfo& device = bench_device(a.device);
        std::vector<Row> rows;
        const double t_start = now_s();
        for (const std::string scene : {"cornell_box", "caustic"}) {
            RenderSettings s;
            s.integrator = Integrator::SPPM;
            s.width = s.height = a.size;
            s.photons = a.photons;
            s.seed = 1000; // the reference: independent of the tracked render's photons
            Render ref(device, scene, s);
            for (uint64_t p = 0; p < a.ref_passes; ++p) ref.integ->run_pass();
            const std::vector<float> ref_y = luminance(ref.integ->image());
            std::fprintf(stderr, "%s: reference of %llu passes done\n", scene.c_str(),
                         (unsigned long long)a.ref_passes);

            s.seed = 1;
            Render r(device, scene, s);
            r.integ->enable_error_estimation();
            const double t0 = now_s();
            for (uint64_t p = 1; p <= a.passes; ++p) {
                r.integ->run_pass();
                const bool sample = p == a.passes || (p >= 4 && (p & (p - 1)) == 0); // 4, 8, 16, ...
                if (!sample) continue;
                ErrorImage e = r.integ->error_estimate(a.confidence);
                std::vector<float> actual(e.absolute.size());
                size_t within = 0;
                std::vector<double> ratio;
                for (size_t i = 0; i < actual.size(); ++i) {
                    actual[i] = std::fabs(e.luminance[i] - ref_y[i]);
                    within += actual[i] <= e.absolute[i];
                    ratio.push_back(e.absolute[i] > 0 ? actual[i] / e.absolute[i] : 0.0);
                }
                std::nth_element(ratio.begin(), ratio.begin() + ratio.size() / 2, ratio.end());
                rows.push_back({scene, p, now_s() - t0, e.image_error,
                                image_error(relative_bounds(actual, e.luminance)),
                                double(within) / double(actual.size()), ratio[ratio.size() / 2]});
                std::fprintf(stderr, "%s pass %llu: estimated %.4f actual %.4f coverage %.3f\n", scene.c_str(),
                             (unsigned long long)p, rows.back().estimated, rows.back().actual, rows.back().coverage);
            }
        }
        std::ofstream csv(a.out + ".csv");
        csv << "scene,pass,seconds,estimated_error_p90,actual_error_p90,fraction_within_bound,median_actual_over_"
               "bound\n";
        std::ostringstream md;
        md << "Device: " << device.name << "; " << a.size << "x" << a.size << ", " << a.photons
           << " photons per pass, SPPM alpha 0.7; reference: " << a.ref_passes << " passes (seed 1000); confidence "
           << a.confidence << "; total " << int(now_s() - t_start) << " s.\n\n"
           << "| scene | pass | s | estimated (p90) | actual (p90) | pixels within bound | median actual/bound |\n"
           << "|---|---:|---:|---:|---:|---:|---:|\n";
        char buf[256];
        for (const Row& r : rows) {
            csv << r.scene << ',' << r.pass << ',' << r.seconds << ',' << r.estimated << ',' << r.actual << ','
                << r.coverage << ',' << r.median_ratio << '\n';
            std::snprintf(buf, sizeof buf, "| %s | %llu | %.1f | %.4f | %.4f | %.1f%% | %.3f |\n", r.scene.c_str(),
                          (unsigned long long)r.pass, r.seconds, r.estimated, r.actual, 100 * r.coverage,
                          r.median_ratio);
            md << buf;
        }
        std::ofstream(a.out + ".md") << md.str();
        std::printf("%s", md.str().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error_calibration: %s\n", e.what());
        return 1;
    }
    return 0;
}
