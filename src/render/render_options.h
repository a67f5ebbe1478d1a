// Everything one render is asked for, whichever front end asks (the command line, the Python
// module): what shapes the image (RenderSettings), when to stop, the world, the devices, and what
// is written or served while it runs. One struct with one set of defaults; render/option_table.h
// fills it from "--name value" pairs, with the checks and messages the command line gives.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "integrators/render_settings.h"
#include "io/stats_json.h"
#include "io/tone_map.h"
#include "scene/environment.h"
#include "scene/medium.h"

namespace clppm {

struct RenderOptions {
    std::string scene;          // .gltf/.glb; empty: the built-in Cornell box
    std::string variant;        // --variant: a KHR_materials_variants name; empty: the default materials
    RenderSettings settings;    // what shapes the image (integrator, size, photons, alpha, seed, ...)
    bool photons_given = false; // --photons was given: the scene does not choose it (kMediaPhotonsPerPass)

    // When to stop. No pass count: the integrator's default (integrator_table.h) without a time
    // limit, unlimited with one. 0 passes: unlimited (needs a time limit).
    std::optional<uint64_t> passes;
    double time_limit = 0.0;          // seconds of rendering; 0: none
    double target_error = 0.0;        // stop once the estimated error is <= E; 0: off
    bool error_bound = false;         // the target applies to the conservative bound instead
    std::optional<double> confidence; // of the error bounds, in (0, 1); none: 0.95

    EnvironmentSettings env;
    MediumSettings medium;
    std::vector<std::string> devices; // --device specs, in order; none: the first GPU, else device 0
    bool generic_kernels = false;     // no scene specialisation
    std::string kernel_dir;           // kernels from here instead of the embedded copies
    std::string dump_kernel_source;   // write the assembled source and build options here

    // Outputs, written atomically. No image path: nothing is written at the end (the command
    // line's default is clppm.exr; the Python module returns the image instead).
    std::string output; // .exr, with a PNG beside it unless !write_png
    bool write_png = true;
    ToneMapping tone{ToneCurve::Aces, 0.0, false}; // the PNG's curve and exposure
    std::string stats_json;
    uint64_t progressive_output = 0;    // save the images every K passes; 0: off
    std::string error_output;           // the per-pixel relative error bound, .exr (and a PNG)
    std::string checkpoint;             // the progressive state, periodically and at the end
    uint64_t checkpoint_every = 0;      // ... every K passes (0: off)
    double checkpoint_interval = 300.0; // ... and every T seconds of rendering
    std::string resume;                 // continue the render of this checkpoint

    // Watching.
    std::string serve;          // [ADDR:]PORT of the live view; empty: off
    std::string display_server; // HOST:PORT of a tev viewer; empty: off
    bool quiet = false;         // no progress line and notes (warnings are always said)
};

constexpr double kDefaultConfidence = 0.95;

// Whether the options ask for progressive error estimation (a target error or an error image).
bool wants_error_estimate(const RenderOptions& options);

// The confidence of the error bounds: the one asked for, else kDefaultConfidence.
double confidence_of(const RenderOptions& options);

// The pass limit for an integrator whose default is `default_passes`; 0: none.
uint64_t pass_limit(const RenderOptions& options, uint64_t default_passes);

// Every file the options will write (image, PNG, stats, checkpoint, error image and its PNG).
std::vector<std::string> output_files(const RenderOptions& options);

// The options every process of an MPI job must share, as JSON keyed by option name (and SCENE):
// the option table's Image and Run options (render/option_table.h), checked by
// render/rank_agreement.h. Not the Local ones: the outputs, which rank 0 alone writes, --device,
// --quiet.
Json options_every_rank_shares(const RenderOptions& options);

// Sets the scene file; throws Error unless it is a .gltf or .glb file, or when one is set already.
void set_scene(RenderOptions& options, const std::string& path);

} // namespace clppm
