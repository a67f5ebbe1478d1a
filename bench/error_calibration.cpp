// error_calibration: how well the progressive error estimate (src/integrators/error_estimate.h) predicts the
// actual error. For each scene (benchmark names, or paths to .gltf files) it renders a reference
// (SPPM, another seed, --ref-photon-factor times the photons, --ref-passes passes; cached as an
// EXR in --ref-cache), then for each integrator a render with error estimation, and at passes
// 4, 8, 16, ... compares, on luminance, the estimates with the actual error against the
// reference: the image-level (90th percentile) bound, the uncalibrated expectation from noise
// alone and from noise and bias, the calibrated estimate --target-error stops on, the actual
// error by the same measure, and the fraction of pixels within their bound (to compare with the
// confidence). Writes a CSV and a markdown table to --out (PREFIX.csv and PREFIX.md). Measures;
// never fails on a number.
//
//   error_calibration [--out PREFIX] [--scenes A,B] [--integrators ppm,sppm,pppm] [--size N]
//                     [--photons M] [--passes N] [--ref-passes N] [--ref-photon-factor K] [--ref-renders K]
//                     [--ref-cache DIR] [--confidence P] [--device SPEC] [--quick]
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.h"
#include "integrators/error_estimate.h"
#include "integrators/integrator_table.h"
#include "io/image_io.h"

using namespace clppm;
using namespace clppm::bench;

namespace {

struct Args {
    std::string out = "error_calibration", device, ref_cache, integrators = "sppm,pppm,ppm";
    std::string scenes = "cornell_box,caustic";
    std::string ref_integrator = "sppm"; // pt: an unbiased reference (its passes are one sample each)
    unsigned size = 48;
    uint64_t photons = 50000, passes = 200, ref_passes = 1600, ref_photon_factor = 4, pt_pass_factor = 16;
    uint64_t ref_renders = 1; // the reference is the mean of this many renders, seeds 1000, 2000, ...
    double confidence = 0.95;
};

// An integrator's name (integrator_row's); "+vi" after one that takes --visual-importance adds it.
std::string parse_integrator(const std::string& name, bool* visual_importance = nullptr) {
    const bool vi = name.size() > 3 && name.compare(name.size() - 3, 3, "+vi") == 0;
    const IntegratorRow* row = nullptr;
    try {
        row = &integrator_row(vi ? name.substr(0, name.size() - 3) : name);
    } catch (const Error& e) {
        throw Error(std::string("--integrators: ") + e.what());
    }
    if (vi && (!visual_importance || !row->visual_importance))
        throw Error("--integrators: " + name + ": only " + visual_importance_integrators() +
                    " take visual importance (+vi)");
    if (visual_importance) *visual_importance = vi;
    return row->name;
}

// A file name part for a scene name or path.
std::string scene_tag(const std::string& scene) {
    std::string t = scene.substr(scene.find_last_of('/') + 1);
    return t.substr(0, t.find('.'));
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    for (std::string t; std::getline(ss, t, ',');)
        if (!t.empty()) v.push_back(t);
    return v;
}

std::vector<float> luminance(const Image& img) {
    std::vector<float> y(size_t(img.width) * img.height);
    for (size_t i = 0; i < y.size(); ++i)
        y[i] = float(0.2126 * img.rgb[3 * i] + 0.7152 * img.rgb[3 * i + 1] + 0.0722 * img.rgb[3 * i + 2]);
    return y;
}

struct Row {
    std::string scene, integrator;
    uint64_t pass;
    double seconds, bound, expected, expected_clean, calibrated, actual, coverage, median_ratio;
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
        else if (k == "--ref-cache") a.ref_cache = next();
        else if (k == "--ref-photon-factor") a.ref_photon_factor = std::stoull(next());
        else if (k == "--ref-renders") a.ref_renders = std::max<uint64_t>(1, std::stoull(next()));
        else if (k == "--integrators") a.integrators = next();
        else if (k == "--pt-pass-factor") a.pt_pass_factor = std::stoull(next());
        else if (k == "--ref-integrator") a.ref_integrator = next();
        else if (k == "--scenes") a.scenes = next();
        else if (k == "--quick") a.size = 16, a.photons = 5000, a.passes = 8, a.ref_passes = 32;
        else {
            std::fprintf(stderr, "error_calibration: unknown argument %s\n", k.c_str());
            return 1;
        }
    }
    try {
        bool vi = false;
        for (const std::string& name : split(a.integrators)) parse_integrator(name, &vi); // refused before any work
        parse_integrator(a.ref_integrator);
        const DeviceInfo& device = bench_device(a.device);
        std::vector<Row> rows;
        const double t_start = now_s();
        for (const std::string& scene : split(a.scenes)) {
            // The reference: SPPM with ref_photon_factor times the photons per pass and another
            // seed, optionally cached as an EXR (it dominates the run time).
            RenderSettings s;
            s.integrator = parse_integrator(a.ref_integrator);
            s.width = s.height = a.size;
            s.photons = a.photons * a.ref_photon_factor;
            // A reference whose own error matters (the path tracer's in a scene lit through a gap)
            // averages --ref-renders renders of seeds 1000, 2000, 3000, ...; each is cached.
            Image ref_img;
            for (uint64_t k = 0; k < a.ref_renders; ++k) {
                s.seed = 1000 * (k + 1);
                const std::string cache = a.ref_cache.empty()
                                              ? std::string()
                                              : a.ref_cache + "/" + scene_tag(scene) + "_" + a.ref_integrator + "_" +
                                                    std::to_string(a.size) + "_" + std::to_string(s.photons) + "x" +
                                                    std::to_string(a.ref_passes) +
                                                    (k ? "_seed" + std::to_string(s.seed) : std::string()) + ".exr";
                Image img;
                if (!cache.empty() && std::ifstream(cache).good()) {
                    img = read_exr(cache);
                } else {
                    Render ref(device, scene, s);
                    for (uint64_t p = 0; p < a.ref_passes; ++p) ref.integ->run_pass();
                    img = ref.integ->image();
                    if (!cache.empty()) write_exr(cache, img);
                }
                if (k == 0) ref_img = img;
                else
                    for (size_t j = 0; j < img.rgb.size(); ++j) ref_img.rgb[j] += img.rgb[j];
            }
            for (float& v : ref_img.rgb) v = float(double(v) / double(a.ref_renders));
            const std::vector<float> ref_y = luminance(ref_img);
            std::fprintf(stderr, "%s: reference of %llu x %llu passes of %llu photons\n", scene_tag(scene).c_str(),
                         (unsigned long long)a.ref_renders, (unsigned long long)a.ref_passes,
                         (unsigned long long)s.photons);

            for (const std::string& name : split(a.integrators)) {
                s.integrator = parse_integrator(name, &s.visual_importance);
                s.photons = a.photons;
                s.seed = 1;
                if (s.integrator == "ppm") s.spp = 4;
                Render r(device, scene, s, false, true);
                const double t0 = now_s();
                // The passes of the path tracer, VCM and BPT are one sample per pixel each, far cheaper
                // than a photon pass: they run --pt-pass-factor times as many (the table shows their
                // real count).
                const uint64_t factor = integrator_row(s.integrator).unit == WorkUnit::Pixels ? a.pt_pass_factor : 1;
                for (uint64_t q = 1; q <= a.passes * factor; ++q) {
                    const uint64_t p = (q + factor - 1) / factor;
                    if (q % factor) {
                        r.integ->run_pass();
                        continue;
                    }
                    r.integ->run_pass();
                    // 4, 6, 8, 12, 16, 24, ...: powers of two and the counts half way between, where
                    // the path tracer's Sobol' passes are no net (kernels/sobol.cl)
                    const uint64_t odd = p % 3 == 0 ? p / 3 : p;
                    const bool sample = p == a.passes || (p >= 4 && (odd & (odd - 1)) == 0);
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
                    rows.push_back({scene_tag(scene), name, r.integ->stats().passes, now_s() - t0, e.image_error,
                                    expected_image_error(e.sigma, {}, e.luminance),
                                    expected_image_error(e.sigma, e.bias_clean, e.luminance), e.expected_error,
                                    image_error(relative_bounds(actual, ref_y)), double(within) / double(actual.size()),
                                    ratio[ratio.size() / 2]});
                    const Row& w = rows.back();
                    std::fprintf(stderr,
                                 "%s %s pass %llu: bound %.4f noise %.4f (+bias %.4f) calibrated %.4f actual %.4f "
                                 "(calibrated/actual %.2f)\n",
                                 scene_tag(scene).c_str(), name.c_str(), (unsigned long long)w.pass, w.bound,
                                 w.expected, w.expected_clean, w.calibrated, w.actual, w.calibrated / w.actual);
                }
            }
        }
        std::ofstream csv(a.out + ".csv");
        csv << "scene,integrator,pass,seconds,bound_p90,expected_p90,expected_with_bias_p90,calibrated_p90,actual_p90,"
               "fraction_within_"
               "bound,median_actual_over_bound\n";
        std::ostringstream md;
        md << "Device: " << device.name << "; " << a.size << "x" << a.size << ", " << a.photons
           << " photons per pass (PPM: --spp 4), alpha 0.7; reference: " << a.ref_integrator << ", " << a.ref_passes
           << " passes of " << a.photons * a.ref_photon_factor << " photons (mean of " << a.ref_renders
           << " renders, seeds 1000, 2000, ...); confidence " << a.confidence << "; total " << int(now_s() - t_start)
           << " s.\n\n"
           << "| scene | integrator | pass | s | bound (p90) | noise only (p90) | noise and bias (p90) | calibrated "
              "estimate (p90) "
              "| actual (p90) | calibrated / actual | pixels within bound | median actual/bound |\n"
           << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        char buf[256];
        for (const Row& r : rows) {
            csv << r.scene << ',' << r.integrator << ',' << r.pass << ',' << r.seconds << ',' << r.bound << ','
                << r.expected << ',' << r.expected_clean << ',' << r.calibrated << ',' << r.actual << ',' << r.coverage
                << ',' << r.median_ratio << '\n';
            std::snprintf(buf, sizeof buf,
                          "| %s | %s | %llu | %.1f | %.4f | %.4f | %.4f | %.4f | %.4f | %.2f | %.1f%% | %.3f |\n",
                          r.scene.c_str(), r.integrator.c_str(), (unsigned long long)r.pass, r.seconds, r.bound,
                          r.expected, r.expected_clean, r.calibrated, r.actual, r.calibrated / r.actual,
                          100 * r.coverage, r.median_ratio);
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
