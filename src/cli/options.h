// The clppm command line: what the user asked for, parsed and range-checked in one place so that
// the renderer only ever sees valid values. Errors are one line naming the option and its range.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/render_settings.h" // Integrator, DirectLighting, PixelFilter
#include "io/tone_map.h"
#include "scene/environment.h"

namespace clppm {

// Without --passes or --time, a render stops after 64 passes; the path tracer's passes are one
// sample per pixel and about 8 times cheaper, so it gets 512 (about the same time at 512x512).
constexpr uint64_t kDefaultPasses = 64, kPtDefaultPasses = 512;

struct Options {
    std::string scene;                             // .gltf/.glb; empty = the embedded Cornell box
    std::string output = "clppm.exr";              // -o/--output, always ends in .exr
    bool write_png = true;                         // false with --no-png
    ToneMapping tone{ToneCurve::Aces, 0.0, false}; // the PNG's --tonemap, --exposure, --auto-exposure
    int width = 0;                                 // 1..16384; 0 = from the camera
    int height = 0;                                // 1..16384; 0 = from the camera
    uint64_t passes = 64;                          // 0 = unlimited (only with --time); 64 when neither is given
    bool passes_default = true;                    // neither --passes nor --time: the path tracer gets kPtDefaultPasses
    double time_limit = 0.0;                       // --time seconds; 0 = none
    uint32_t photons_per_pass = 200000;            // --photons, 1..2^31-1
    double alpha = 0.7;                            // in (0, 1]
    double radius = 0.0;                           // initial radius R0; 0 = heuristic
    uint64_t seed = 1;
    bool list_devices = false;
    std::vector<std::string> devices; // --device, repeatable, in the order given
    int camera = 0;                   // glTF camera index
    bool quiet = false;
    std::string stats_json;                   // --stats-json FILE; empty = none
    Integrator integrator = Integrator::SPPM; // with integrator_auto, what the scene decides (default_integrator.h)
    bool integrator_auto = true;              // no --integrator, or --integrator auto
    DirectLighting direct = DirectLighting::Sample;
    int spp = 4; // PPM hit points (samples) per pixel, 1..256: 4 anti-alias (bench/RESULTS.md)
    PixelFilter filter = PixelFilter::Box;
    double aperture = -1.0;      // thin-lens aperture radius; < 0 = the camera's (0 = pinhole)
    double focus_distance = 0.0; // thin-lens focus distance; 0 = the camera's
    int max_bounces = 16;        // 1..1024
    EnvironmentSettings env;     // --env, --env-color, --env-strength, --env-rotate, --env-hidden, --no-default-light
    uint64_t progressive_output = 0;    // save every K passes; 0 = off
    std::string checkpoint;             // --checkpoint FILE: save the progressive state here
    uint64_t checkpoint_every = 0;      // ... every K passes (0: off)
    double checkpoint_interval = 300.0; // ... and every T seconds of rendering
    std::string resume;                 // --resume FILE: continue a checkpointed render
    bool generic_kernels = false;       // --generic-kernels: no scene specialisation
    std::string kernel_dir;             // load kernels from here instead of the embedded copies
    std::string dump_kernel_source;     // write the assembled kernel source and build options here
    double target_error = 0.0;          // --target-error E: stop once the estimated error is <= E; 0 = off
    bool error_bound = false;           // --error-bound: --target-error stops on the conservative bound
    double confidence = 0.95;           // --confidence P of the error bound, in (0, 1)
    std::string error_output;           // --error-output FILE.exr: the per-pixel relative error bound
    std::string serve;                  // --serve [ADDR:]PORT: the live view (cli/live_view.h); empty = off
    std::string display_server;         // --display-server HOST:PORT: updates to tev (cli/tev_client.h)
    bool help = false;                  // -h/--help: print usage() and exit
    bool version = false;               // --version: print the version and exit
};

// Parses argv[1..argc-1]. Both "--opt value" and "--opt=value" are accepted. Parsing stops at
// -h/--help or --version (the flag is set, the rest is ignored). Throws clppm::Error with one line
// such as "--alpha 1.5: must be in (0, 1]" or "unknown option --foo (see --help)".
Options parse_options(int argc, char** argv);

// Whether the options ask for progressive error estimation (--target-error or --error-output).
bool wants_error_estimate(const Options& options);

// The same on already split arguments (without the program name); used by the tests.
Options parse_options(const std::vector<std::string>& args);

// Usage text listing every option with its range and default.
std::string usage();

} // namespace clppm
