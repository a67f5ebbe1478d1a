#include "cli/options.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/help_formatter.h"
#include "cli/live_view.h"
#include "util/error.h"

namespace clppm {
namespace {

struct OptionSpec;

struct ParseState {
    Options options;
    bool passes_given = false;
    bool confidence_given = false;
    std::map<const OptionSpec*, std::string> shown; // the spelling typed last ("-o" or "--output"), for messages
};

// One option occurrence: the spec, the spelling the user typed ("-o" or "--output") and its value.
struct Arg {
    const OptionSpec& spec;
    const std::string& shown;
    const std::string& value;
};

// One table drives both the parser (a CLI11 App built from it) and usage(), so the help text
// cannot drift from what is accepted. `range` is also the tail of every error message:
// "--alpha 1.5: must be <range>". Entries are in --help order, grouped.
struct OptionSpec {
    const char* group;      // the --help section: "Output", "Integrator", ...
    const char* name;       // "--alpha"
    const char* short_name; // "-o", or nullptr
    const char* metavar;    // "A"; nullptr for a flag
    const char* help;
    const char* range; // nullptr when any value goes
    const char* default_text;
    void (*apply)(ParseState&, const Arg&);
};

[[noreturn]] void bad_value(const Arg& a) {
    std::string shown_value = a.value.empty() ? "''" : a.value;
    throw Error(a.shown + " " + shown_value + ": must be " + a.spec.range);
}

int64_t parse_int(const Arg& a, int64_t lo, int64_t hi) {
    const std::string& v = a.value;
    if (v.empty() || !(std::isdigit(static_cast<unsigned char>(v[0])) || v[0] == '-' || v[0] == '+')) bad_value(a);
    errno = 0;
    char* end = nullptr;
    long long n = std::strtoll(v.c_str(), &end, 10);
    if (errno == ERANGE || *end != '\0' || n < lo || n > hi) bad_value(a);
    return n;
}

// strtoull accepts "-1" (and wraps it), so the sign is rejected first.
uint64_t parse_u64(const Arg& a) {
    const std::string& v = a.value;
    if (v.empty() || !std::isdigit(static_cast<unsigned char>(v[0]))) bad_value(a);
    errno = 0;
    char* end = nullptr;
    unsigned long long n = std::strtoull(v.c_str(), &end, 10);
    if (errno == ERANGE || *end != '\0') bad_value(a);
    return n;
}

// Finite reals only: "nan" and "inf" parse with strtod but are never meaningful here.
double parse_real(const Arg& a, bool (*ok)(double)) {
    const std::string& v = a.value;
    if (v.empty() || std::isspace(static_cast<unsigned char>(v[0]))) bad_value(a);
    errno = 0;
    char* end = nullptr;
    double x = std::strtod(v.c_str(), &end);
    if (errno == ERANGE || *end != '\0' || !std::isfinite(x) || !ok(x)) bad_value(a);
    return x;
}

// "R,G,B": three finite numbers >= 0.
std::array<float, 3> parse_rgb(const Arg& a) {
    std::array<float, 3> c{};
    const std::string& v = a.value;
    size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const size_t comma = v.find(',', start);
        if ((k < 2) != (comma != std::string::npos)) bad_value(a);
        const std::string part = v.substr(start, k < 2 ? comma - start : std::string::npos);
        if (part.empty() || std::isspace(static_cast<unsigned char>(part[0]))) bad_value(a);
        errno = 0;
        char* end = nullptr;
        const double x = std::strtod(part.c_str(), &end);
        if (errno == ERANGE || *end != '\0' || !std::isfinite(x) || x < 0 || !std::isfinite(float(x))) bad_value(a);
        c[size_t(k)] = float(x);
        start = comma + 1;
    }
    return c;
}

// A choice's value as typed, lower-cased: choices are case-insensitive ("--integrator SPPM").
std::string lower(const std::string& v) {
    std::string out(v);
    for (char& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return out;
}

const std::string& non_empty(const Arg& a) {
    if (a.value.empty()) bad_value(a);
    return a.value;
}

bool ends_with_ci(const std::string& s, const char* suffix) {
    std::string suf(suffix);
    if (s.size() < suf.size()) return false;
    for (size_t i = 0; i < suf.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[s.size() - suf.size() + i])) != suf[i]) return false;
    return true;
}

void set_scene(ParseState& st, const std::string& path) {
    if (!st.options.scene.empty())
        throw Error("unexpected second scene file " + path + " (already given " + st.options.scene + ")");
    if (!ends_with_ci(path, ".gltf") && !ends_with_ci(path, ".glb"))
        throw Error("scene file " + path + ": must be a .gltf or .glb file");
    st.options.scene = path;
}

const OptionSpec kOptions[] = {
    {"Output", "--output", "-o", "FILE", "Output image (a PNG preview is written beside it)",
     "a file name ending in .exr", "clppm.exr",
     [](ParseState& st, const Arg& a) {
         if (!ends_with_ci(a.value, ".exr") || a.value.size() <= 4) bad_value(a);
         st.options.output = a.value;
     }},
    {"Output", "--no-png", nullptr, nullptr, "Do not write the PNG preview", nullptr, nullptr,
     [](ParseState& st, const Arg&) { st.options.write_png = false; }},
    {"Output", "--tonemap", nullptr, "CURVE",
     "The PNG's tone curve: clip = linear up to white, aces = a filmic curve (Narkowicz's ACES fit), "
     "reinhard = x / (1 + x); the EXR stays linear",
     "clip, aces or reinhard", "aces",
     [](ParseState& st, const Arg& a) {
         if (!parse_tone_curve(a.value, &st.options.tone.curve)) bad_value(a);
     }},
    {"Output", "--exposure", nullptr, "EV",
     "The PNG's exposure in stops (x 2^EV before the tone curve; with --auto-exposure, added to it)",
     "a number in -64..64", "0",
     [](ParseState& st, const Arg& a) {
         st.options.tone.exposure_ev = parse_real(a, [](double x) { return x >= -64 && x <= 64; });
     }},
    {"Output", "--auto-exposure", nullptr, nullptr,
     "Expose the PNG so that the image's log-average luminance shows as middle grey (0.18)", nullptr, nullptr,
     [](ParseState& st, const Arg&) { st.options.tone.auto_exposure = true; }},
    {"Output", "--stats-json", nullptr, "FILE", "Write render statistics as JSON", "a file name", "none",
     [](ParseState& st, const Arg& a) { st.options.stats_json = non_empty(a); }},
    {"Output", "--progressive-output", nullptr, "K", "Also save the images every K passes", "an integer >= 0 (0 = off)",
     "0",
     [](ParseState& st, const Arg& a) {
         st.options.progressive_output = static_cast<uint64_t>(parse_int(a, 0, INT64_MAX));
     }},
    {"Output", "--serve", nullptr, "[ADDR:]PORT",
     "Serve a live view of the render at http://ADDR:PORT/ (image, progress, error map, save and stop buttons); "
     "ADDR defaults to 127.0.0.1, PORT 0 picks a free port",
     "[ADDR:]PORT with a port in 0..65535", "off",
     [](ParseState& st, const Arg& a) {
         parse_serve_address(a.value); // checked now: a typo fails before the scene loads
         st.options.serve = a.value;
     }},
    {"Output", "--display-server", nullptr, "HOST:PORT",
     "Send the image as it converges to the tev viewer listening at HOST:PORT (tev's own protocol, as pbrt-v4's "
     "--display-server; tev listens on 127.0.0.1:14158)",
     "HOST:PORT", "off", [](ParseState& st, const Arg& a) { st.options.display_server = non_empty(a); }},
    {"Output", "--quiet", nullptr, nullptr, "No progress output", nullptr, nullptr,
     [](ParseState& st, const Arg&) { st.options.quiet = true; }},
    {"Image and camera", "--width", nullptr, "N", "Image width in pixels",
     "an integer in 0..16384 (0 = from the camera)", "0",
     [](ParseState& st, const Arg& a) { st.options.width = static_cast<int>(parse_int(a, 0, 16384)); }},
    {"Image and camera", "--height", nullptr, "N", "Image height in pixels",
     "an integer in 0..16384 (0 = from the camera)", "0",
     [](ParseState& st, const Arg& a) { st.options.height = static_cast<int>(parse_int(a, 0, 16384)); }},
    {"Image and camera", "--camera", nullptr, "N", "Index of the glTF camera to render through", "an integer >= 0", "0",
     [](ParseState& st, const Arg& a) { st.options.camera = static_cast<int>(parse_int(a, 0, INT_MAX)); }},
    {"Image and camera", "--aperture", nullptr, "R", "Thin-lens aperture radius in scene units (depth of field)",
     "a finite number >= 0 (0 = pinhole)", "the camera's, else 0",
     [](ParseState& st, const Arg& a) { st.options.aperture = parse_real(a, [](double x) { return x >= 0; }); }},
    {"Image and camera", "--focus-distance", nullptr, "D", "Distance to the plane in focus, in scene units",
     "a finite number > 0", "the camera's, else the scene centre's distance",
     [](ParseState& st, const Arg& a) { st.options.focus_distance = parse_real(a, [](double x) { return x > 0; }); }},
    {"Image and camera", "--filter", nullptr, "NAME",
     "Pixel filter, importance-sampled: box = the pixel's square, tent = separable tent of radius 1 pixel",
     "box or tent", "box",
     [](ParseState& st, const Arg& a) {
         const std::string v = lower(a.value);
         if (v == "box") st.options.filter = PixelFilter::Box;
         else if (v == "tent") st.options.filter = PixelFilter::Tent;
         else bad_value(a);
     }},
    {"Integrator", "--integrator", nullptr, "NAME",
     "Integrator: auto = sppm for a scene with lights of its own, pt for one lit only by an environment "
     "(measured: bench/RESULTS.md); ppm = progressive photon mapping, sppm = stochastic PPM, pppm = "
     "probabilistic PPM (independent passes), pt = path tracing, vcm = vertex connection and merging (bidirectional "
     "path tracing and photon merging under MIS), bpt = bidirectional path tracing",
     "auto, ppm, sppm, pppm, pt, vcm or bpt", "auto",
     [](ParseState& st, const Arg& a) {
         const std::string v = lower(a.value);
         st.options.integrator_auto = false;
         if (v == "auto") st.options.integrator_auto = true, st.options.integrator = Integrator::SPPM;
         else if (v == "ppm") st.options.integrator = Integrator::PPM;
         else if (v == "sppm") st.options.integrator = Integrator::SPPM;
         else if (v == "pppm") st.options.integrator = Integrator::PPPM;
         else if (v == "pt") st.options.integrator = Integrator::PT;
         else if (v == "vcm") st.options.integrator = Integrator::VCM;
         else if (v == "bpt" || v == "bdpt") st.options.integrator = Integrator::BPT; // bdpt: pbrt's name
         else bad_value(a);
     }},
    {"Integrator", "--passes", nullptr, "N", "Stop after N passes (with --time: whichever comes first)",
     "an integer >= 1 (0 = unlimited, with --time)", "64 (512 for pt), or unlimited with --time",
     [](ParseState& st, const Arg& a) {
         st.options.passes = static_cast<uint64_t>(parse_int(a, 0, INT64_MAX));
         st.passes_given = true;
     }},
    {"Integrator", "--time", nullptr, "SECONDS", "Stop after this much render time", "a number of seconds > 0", "none",
     [](ParseState& st, const Arg& a) { st.options.time_limit = parse_real(a, [](double x) { return x > 0; }); }},
    {"Integrator", "--photons", nullptr, "N", "Photons traced per pass", "an integer in 1..2147483647", "200000",
     [](ParseState& st, const Arg& a) {
         st.options.photons_per_pass = static_cast<uint32_t>(parse_int(a, 1, INT32_MAX));
     }},
    // alpha of Hachisuka et al. 2008 (radius reduction): R^2 <- R^2 (N + alpha M) / (N + M).
    {"Integrator", "--alpha", nullptr, "A", "Fraction of new photons kept per pass (radius reduction)", "in (0, 1]",
     "0.7",
     [](ParseState& st, const Arg& a) { st.options.alpha = parse_real(a, [](double x) { return x > 0 && x <= 1; }); }},
    {"Integrator", "--radius", nullptr, "R", "Initial gather radius R0 in scene units",
     "a finite number >= 0 (0 = heuristic)", "0",
     [](ParseState& st, const Arg& a) { st.options.radius = parse_real(a, [](double x) { return x >= 0; }); }},
    {"Integrator", "--spp", nullptr, "N", "Hit points (samples) per pixel per pass", "an integer in 1..256", "4",
     [](ParseState& st, const Arg& a) { st.options.spp = static_cast<int>(parse_int(a, 1, 256)); }},
    {"Integrator", "--direct", nullptr, "MODE",
     "Direct light from photons (density estimate) or by sampling lights at hit points", "photons or sample", "sample",
     [](ParseState& st, const Arg& a) {
         const std::string v = lower(a.value);
         if (v == "photons") st.options.direct = DirectLighting::Photons;
         else if (v == "sample") st.options.direct = DirectLighting::Sample;
         else bad_value(a);
     }},
    {"Integrator", "--max-bounces", nullptr, "N", "Longest eye or photon path", "an integer in 1..1024", "16",
     [](ParseState& st, const Arg& a) { st.options.max_bounces = static_cast<int>(parse_int(a, 1, 1024)); }},
    {"Integrator", "--seed", nullptr, "S", "Random seed", "an integer in 0..18446744073709551615", "1",
     [](ParseState& st, const Arg& a) { st.options.seed = parse_u64(a); }},
    // Hachisuka, Jarosz and Jensen 2010: per-pixel bias and noise (integrators/error_estimate.h).
    {"Error estimation", "--target-error", nullptr, "E",
     "Stop once the estimated error is at most E: the 90th percentile over pixels of |L - L_true| / L, "
     "calibrated so that the actual error at the stop is between E/2 and E; --passes and --time still "
     "bound the render",
     "a number > 0", "none",
     [](ParseState& st, const Arg& a) { st.options.target_error = parse_real(a, [](double x) { return x > 0; }); }},
    {"Error estimation", "--error-bound", nullptr, nullptr,
     "With --target-error: stop on the conservative bound instead (the 90th percentile of per-pixel bounds "
     "that hold at --confidence; typically 3 to 4 times the actual error)",
     nullptr, nullptr, [](ParseState& st, const Arg&) { st.options.error_bound = true; }},
    {"Error estimation", "--confidence", nullptr, "P",
     "Confidence of the per-pixel error bounds (with --target-error or --error-output)", "in (0, 1)", "0.95",
     [](ParseState& st, const Arg& a) {
         st.options.confidence = parse_real(a, [](double x) { return x > 0 && x < 1; });
         st.confidence_given = true;
     }},
    {"Error estimation", "--error-output", nullptr, "FILE",
     "Write the per-pixel relative error bound to FILE (EXR) and a false-colour PNG beside it; the main "
     "EXR gets an \"error\" layer too",
     "a file name ending in .exr", "none",
     [](ParseState& st, const Arg& a) {
         if (!ends_with_ci(a.value, ".exr") || a.value.size() <= 4) bad_value(a);
         st.options.error_output = a.value;
     }},
    {"Lighting", "--env", nullptr, "FILE",
     "Light the scene with an equirectangular environment map (top row +Y, centre -Z, u towards +X)",
     "an .exr or .hdr file", "none", [](ParseState& st, const Arg& a) { st.options.env.file = non_empty(a); }},
    {"Lighting", "--env-color", nullptr, "R,G,B", "Light the scene with a uniform environment of this radiance",
     "three numbers >= 0, comma-separated", "none",
     [](ParseState& st, const Arg& a) {
         st.options.env.color = parse_rgb(a);
         st.options.env.has_color = true;
     }},
    {"Lighting", "--env-strength", nullptr, "S", "Scale the environment (also the default one)", "a finite number >= 0",
     "1",
     [](ParseState& st, const Arg& a) { st.options.env.strength = parse_real(a, [](double x) { return x >= 0; }); }},
    {"Lighting", "--env-rotate", nullptr, "DEG", "Turn the environment about +Y (right-handed: +X towards -Z)",
     "a finite number of degrees", "0",
     [](ParseState& st, const Arg& a) { st.options.env.rotate_degrees = parse_real(a, [](double) { return true; }); }},
    {"Lighting", "--env-hidden", nullptr, nullptr,
     "Camera rays that leave the scene see black; the environment still lights it", nullptr, nullptr,
     [](ParseState& st, const Arg&) { st.options.env.hidden = true; }},
    {"Lighting", "--no-default-light", nullptr, nullptr,
     "Refuse a scene without lights instead of lighting it with a uniform white environment of radiance 1", nullptr,
     nullptr, [](ParseState& st, const Arg&) { st.options.env.default_light = false; }},
    {"Checkpoints", "--checkpoint", nullptr, "FILE",
     "Save the complete progressive state to FILE (atomically) periodically, on Ctrl-C and at the end", "a file name",
     "none", [](ParseState& st, const Arg& a) { st.options.checkpoint = non_empty(a); }},
    {"Checkpoints", "--checkpoint-every", nullptr, "K", "Save the checkpoint every K passes",
     "an integer >= 0 (0 = off)", "0",
     [](ParseState& st, const Arg& a) {
         st.options.checkpoint_every = static_cast<uint64_t>(parse_int(a, 0, INT64_MAX));
     }},
    {"Checkpoints", "--checkpoint-interval", nullptr, "SECONDS", "Save the checkpoint every SECONDS of rendering",
     "a number of seconds > 0", "300",
     [](ParseState& st, const Arg& a) {
         st.options.checkpoint_interval = parse_real(a, [](double x) { return x > 0; });
     }},
    {"Checkpoints", "--resume", nullptr, "FILE",
     "Continue the render saved in checkpoint FILE (same scene and image-shaping options; --passes "
     "counts from the start of the original render, --time this run only)",
     "a checkpoint file", "none", [](ParseState& st, const Arg& a) { st.options.resume = non_empty(a); }},
    {"Devices and kernels", "--list-devices", nullptr, nullptr, "List the OpenCL devices and exit", nullptr, nullptr,
     [](ParseState& st, const Arg&) { st.options.list_devices = true; }},
    {"Devices and kernels", "--device", nullptr, "SPEC", "Device to render on; repeatable (see --list-devices)",
     "a device index, cpu, gpu or part of a device name", "automatic",
     [](ParseState& st, const Arg& a) { st.options.devices.push_back(non_empty(a)); }},
    {"Devices and kernels", "--generic-kernels", nullptr, nullptr,
     "Build the generic kernels instead of ones specialised for the scene's materials, lights and camera", nullptr,
     nullptr, [](ParseState& st, const Arg&) { st.options.generic_kernels = true; }},
    {"Devices and kernels", "--kernel-dir", nullptr, "DIR", "Load kernels from DIR instead of the embedded copies",
     "a directory", "embedded", [](ParseState& st, const Arg& a) { st.options.kernel_dir = non_empty(a); }},
    {"Devices and kernels", "--dump-kernel-source", nullptr, "FILE",
     "Write the assembled kernel source and build options to FILE", "a file name", "none",
     [](ParseState& st, const Arg& a) { st.options.dump_kernel_source = non_empty(a); }},
    {"Other", "--help", "-h", nullptr, "Print this help and exit", nullptr, nullptr,
     [](ParseState& st, const Arg&) { st.options.help = true; }},
    {"Other", "--version", nullptr, nullptr, "Print the version and exit", nullptr, nullptr,
     [](ParseState& st, const Arg&) { st.options.version = true; }},
};

const OptionSpec* find_option(const std::string& name) {
    for (const OptionSpec& spec : kOptions)
        if (name == spec.name || (spec.short_name && name == spec.short_name)) return &spec;
    return nullptr;
}

// Levenshtein distance, for suggestions.
size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// "unknown option --pases (did you mean --passes? see --help)": the nearest long name within a
// third of its length in edits (at least 1, at most 3), else no suggestion.
[[noreturn]] void unknown_option(const std::string& name) {
    const OptionSpec* best = nullptr;
    size_t best_distance = 0;
    for (const OptionSpec& spec : kOptions) {
        const size_t d = edit_distance(name, spec.name);
        if (!best || d < best_distance) best = &spec, best_distance = d;
    }
    const size_t allowed = std::clamp<size_t>(std::string(best->name).size() / 3, 1, 3);
    if (name.rfind("--", 0) == 0 && best_distance <= allowed)
        throw Error("unknown option " + name + " (did you mean " + best->name + "? see --help)");
    throw Error("unknown option " + name + " (see --help)");
}

// Whether a token is itself an option (so it cannot be the previous option's value): "--name" or
// "--name=..." or "-o" with a known name. Negative numbers are values.
bool is_option_token(const std::string& token) {
    if (token.rfind("--", 0) == 0) return find_option(token.substr(0, token.find('='))) != nullptr;
    return token.size() >= 2 && token[0] == '-' && find_option(token.substr(0, 2)) != nullptr &&
           (token.size() == 2 || token[2] == '=');
}

// "--passes" defaults to 64 only when no --time bounds the render; 0 passes needs a time limit.
void resolve_limits(ParseState& st) {
    Options& o = st.options;
    if (st.passes_given && o.passes == 0 && o.time_limit <= 0) throw Error("--passes 0: unlimited passes need --time");
    if (!st.passes_given) o.passes = o.time_limit > 0 ? 0 : kDefaultPasses;
    o.passes_default = !st.passes_given && !(o.time_limit > 0);
}

// Every integrator estimates its error; --confidence means nothing without an estimate,
// --error-bound nothing without a target.
void check_error_options(const ParseState& st) {
    const Options& o = st.options;
    const char* asked = o.target_error > 0 ? "--target-error" : !o.error_output.empty() ? "--error-output" : nullptr;
    if (o.error_bound && !(o.target_error > 0)) throw Error("--error-bound: needs --target-error");
    if (!asked && st.confidence_given) throw Error("--confidence: needs --target-error or --error-output");
}

constexpr size_t kHelpColumn = 30, kHelpWidth = 100;

// The environment variables clppm reads, for the end of --help.
std::string environment_help() {
    const char* env[][2] = {
        {"CLPPM_KERNEL_DIR", "load the kernel sources from this folder instead of the embedded copies"},
        {"CLPPM_CACHE_DIR", "where built programs are cached (else $XDG_CACHE_HOME/clppm, else ~/.cache/clppm; not for "
                            "PoCL, which keeps its own)"},
        {"CLPPM_NO_CACHE", "1: build the kernels every time, cache nothing"},
        {"CLPPM_BUILD_LOG", "1: print the compiler's log of successful kernel builds"},
        {"CLPPM_LOCAL_SIZE", "force this work-group size (the image does not change)"},
        {"CLPPM_PHOTON_BATCH", "trace each pass's photons in batches of at most this many (the image does not change)"},
        {"POCL_DEVICES", "PoCL's devices, e.g. \"pthread pthread\" for two CPU devices (--device all)"}};
    std::string out = "Environment:\n";
    for (const auto& [name, what] : env) {
        std::string line = std::string("  ") + name;
        line += std::string(kHelpColumn > line.size() ? kHelpColumn - line.size() : 1, ' ');
        std::string text = wrapped(what, kHelpWidth - kHelpColumn);
        for (size_t p = text.find('\n'); p != std::string::npos; p = text.find('\n', p + 1))
            text.insert(p + 1, std::string(kHelpColumn, ' '));
        out += line + text + "\n";
    }
    return out;
}

// The description column of an option: its help, range and default, wrapped.
std::string option_description(const OptionSpec& spec) {
    std::string text = spec.help;
    if (spec.range && spec.metavar) text += std::string(". Must be ") + spec.range;
    if (spec.default_text) text += std::string(". Default: ") + spec.default_text;
    return wrapped(text + ".", kHelpWidth - kHelpColumn - 2);
}

// The command line as a CLI11 App over `st`: one option per table entry, its callback the entry's
// apply, run as each occurrence is parsed (so, as before, left to right, the last one winning and
// --device collecting every one); the scene files as a positional; render and compare as
// subcommands (render is the default; compare has its own parser, compare_command).
std::unique_ptr<CLI::App> make_app(ParseState& st, std::vector<std::string>& scenes) {
    auto app = std::make_unique<CLI::App>(
        "Renders SCENE (default: the built-in Cornell box) with progressive photon mapping in OpenCL.\n"
        "Values may be given as --opt VALUE or --opt=VALUE (-o FILE or -o=FILE); choices ignore case.",
        "clppm");
    app->set_help_flag(); // --help is a table entry: it stops parsing, as --version does
    app->formatter(
        std::make_shared<HelpFormatter>("Usage: clppm [render] [options] [SCENE.gltf|SCENE.glb]\n"
                                        "       clppm compare IMAGE.exr REFERENCE.exr [--diff OUT.png] [--box K]\n",
                                        kHelpColumn));
    app->add_subcommand("render", "Render a scene (the default: `clppm [options] SCENE` is the same)");
    app->add_subcommand("compare", "How far an image is from a reference, as JSON (clppm compare --help)");
    app->add_option("SCENE", scenes, "A .gltf or .glb file; none renders the built-in Cornell box")
        ->group("Scene")
        ->type_name("");
    for (const OptionSpec& spec : kOptions) {
        const std::string names = spec.short_name ? std::string(spec.short_name) + "," + spec.name : spec.name;
        st.shown.emplace(&spec, spec.name);
        const std::string& typed = st.shown.at(&spec); // map nodes stay put
        CLI::Option* opt;
        if (spec.metavar) {
            opt = app->add_option_function<std::string>(
                names,
                [&st, &spec, &typed](const std::string& v) {
                    spec.apply(st, Arg{spec, typed, v});
                },
                option_description(spec));
            opt->type_name(spec.metavar);
        } else {
            opt = app->add_flag_function(
                names,
                [&st, &spec, &typed](int64_t) {
                    spec.apply(st, Arg{spec, typed, std::string()});
                },
                option_description(spec));
        }
        opt->group(spec.group)->trigger_on_parse()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    }
    app->footer(environment_help());
    return app;
}

// What CLI11 leaves to us, checked before it parses, left to right, so that the messages are
// clppm's: an unknown option (with a suggestion), a flag given a value, a missing value (an
// option where the value should be is not taken as the value: "--passes --quiet"), and -h,
// --help or --version, which end the parse (what follows is not looked at). The result is the
// arguments in one canonical form for CLI11: "--name VALUE" or "--flag", the scene files last
// after "--" (so no file name is taken for an option or a subcommand).
std::vector<std::string> canonical_arguments(ParseState& st, const std::vector<std::string>& args) {
    std::vector<std::string> out, scenes;
    bool options_ended = false; // after "--" everything is a scene file
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (!options_ended && arg == "--") {
            options_ended = true;
            continue;
        }
        if (options_ended || arg.size() < 2 || arg[0] != '-') {
            scenes.push_back(arg);
            continue;
        }
        // "--name=value", and "-o=value" for the short forms.
        const size_t eq =
            arg.rfind("--", 0) == 0 ? arg.find('=') : (arg.size() > 2 && arg[2] == '=' ? 2 : std::string::npos);
        const std::string name = arg.substr(0, eq);
        const OptionSpec* spec = find_option(name);
        if (!spec) unknown_option(name);
        if (spec->name == std::string("--help") || spec->name == std::string("--version")) {
            if (eq != std::string::npos) throw Error(name + " takes no value");
            (spec->name == std::string("--help") ? st.options.help : st.options.version) = true;
            break;
        }
        out.push_back(spec->name);
        if (!spec->metavar) {
            if (eq != std::string::npos) throw Error(name + " takes no value");
        } else if (eq != std::string::npos) {
            out.push_back(arg.substr(eq + 1));
        } else if (i + 1 < args.size() && !is_option_token(args[i + 1])) {
            out.push_back(args[++i]);
        } else {
            throw Error(name + ": missing value " + spec->metavar + " (must be " + spec->range + ")");
        }
        // The spelling the messages name; CLI11 applies the occurrences in order, so the
        // spelling of each would need a token of its own: the last one typed is a fair name.
        st.shown[spec] = name;
    }
    out.push_back("--");
    out.insert(out.end(), scenes.begin(), scenes.end());
    return out;
}

} // namespace

Options parse_options(const std::vector<std::string>& given) {
    std::vector<std::string> args = given;
    if (!args.empty() && args[0] == "render") args.erase(args.begin()); // `clppm render ...` = `clppm ...`
    ParseState st;
    std::vector<std::string> scenes;
    std::unique_ptr<CLI::App> app = make_app(st, scenes);
    std::vector<std::string> tokens = canonical_arguments(st, args);
    std::reverse(tokens.begin(), tokens.end()); // CLI11 takes a vector last argument first
    try {
        app->parse(tokens);
    } catch (const CLI::ParseError& e) {
        // canonical_arguments leaves CLI11 nothing to refuse; should it, the message is one line.
        throw Error(std::string("command line: ") + e.what());
    }
    for (const std::string& scene : scenes) set_scene(st, scene);
    if (st.options.help || st.options.version) return st.options;
    resolve_limits(st);
    check_error_options(st);
    return st.options;
}

bool wants_error_estimate(const Options& o) { return o.target_error > 0 || !o.error_output.empty(); }

Options parse_options(int argc, char** argv) {
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
    return parse_options(args);
}

std::string usage() {
    ParseState st;
    std::vector<std::string> scenes;
    return make_app(st, scenes)->help();
}

} // namespace clppm
