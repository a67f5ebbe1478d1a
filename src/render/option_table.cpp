#include "render/option_table.h"

#include <algorithm>
#include <climits>
#include <cstdint>

#include "integrators/default_integrator.h"
#include "integrators/integrator_table.h"
#include "render/live_view.h"
#include "util/error.h"

namespace clppm {

namespace {

bool is_integrator(const std::string& v) {
    for (const IntegratorRow& row : integrator_table())
        if (v == row.name || (row.alias && v == row.alias)) return true;
    return false;
}

const std::string& integrator_range() {
    static const std::string s = "auto, " + integrator_names();
    return s;
}

const std::string& integrator_help() {
    static const std::string s = [] {
        std::string h = std::string("Integrator: auto = the fastest for the scene (") + kDefaultIntegratorRule + ")";
        for (const IntegratorRow& row : integrator_table()) h += std::string("; ") + row.name + " = " + row.summary;
        return h;
    }();
    return s;
}

const std::string& default_passes_text() {
    // "64 (ppm, sppm, pppm), 512 (pt), 16 (vcm, bpt)": the integrators grouped by their default.
    static const std::string s = [] {
        std::vector<std::pair<uint64_t, std::string>> groups;
        for (const IntegratorRow& row : integrator_table()) {
            auto g = std::find_if(groups.begin(), groups.end(),
                                  [&](const auto& p) { return p.first == row.default_passes; });
            if (g == groups.end()) groups.emplace_back(row.default_passes, row.name);
            else g->second += std::string(", ") + row.name;
        }
        std::string text;
        for (const auto& [passes, names] : groups) text += std::to_string(passes) + " (" + names + "), ";
        return text + "unlimited with --time";
    }();
    return s;
}

} // namespace

const std::vector<RenderOptionSpec>& render_option_table() {
    static const std::vector<RenderOptionSpec> table = {
        {"Output", "--output", "-o", "FILE", "Output image (a PNG preview is written beside it)",
         "a file name ending in .exr", "clppm.exr (the command line; none from Python)",
         [](RenderOptions& o, const OptionArg& a) {
             if (!ends_with_ci(a.value, ".exr") || a.value.size() <= 4) bad_value(a);
             o.output = a.value;
         },
         OptionRole::Local, nullptr},
        {"Output", "--no-png", nullptr, nullptr, "Do not write the PNG preview", nullptr, nullptr,
         [](RenderOptions& o, const OptionArg&) { o.write_png = false; }, OptionRole::Local, nullptr},
        {"Output", "--tonemap", nullptr, "CURVE",
         "The PNG's tone curve: clip = linear up to white, aces = a filmic curve (Narkowicz's ACES fit), "
         "reinhard = x / (1 + x); the EXR stays linear",
         enum_range<ToneCurve>(), "aces",
         [](RenderOptions& o, const OptionArg& a) { o.tone.curve = parse_enum<ToneCurve>(a); }, OptionRole::Local,
         nullptr},
        {"Output", "--exposure", nullptr, "EV",
         "The PNG's exposure in stops (x 2^EV before the tone curve; with --auto-exposure, added to it)",
         "a number in -64..64", "0",
         [](RenderOptions& o, const OptionArg& a) {
             o.tone.exposure_ev = parse_real(a, [](double x) { return x >= -64 && x <= 64; });
         },
         OptionRole::Local, nullptr},
        {"Output", "--auto-exposure", nullptr, nullptr,
         "Expose the PNG so that the image's log-average luminance shows as middle grey (0.18)", nullptr, nullptr,
         [](RenderOptions& o, const OptionArg&) { o.tone.auto_exposure = true; }, OptionRole::Local, nullptr},
        {"Output", "--stats-json", nullptr, "FILE", "Write render statistics as JSON", "a file name", "none",
         [](RenderOptions& o, const OptionArg& a) { o.stats_json = non_empty(a); }, OptionRole::Local, nullptr},
        {"Output", "--progressive-output", nullptr, "K", "Also save the images every K passes",
         "an integer >= 0 (0 = off)", "0",
         [](RenderOptions& o, const OptionArg& a) {
             o.progressive_output = static_cast<uint64_t>(parse_int(a, 0, INT64_MAX));
         },
         OptionRole::Local, nullptr},
        {"Output", "--serve", nullptr, "[ADDR:]PORT",
         "Serve a live view of the render at http://ADDR:PORT/ (image, progress, error map, save and stop buttons); "
         "ADDR defaults to 127.0.0.1, PORT 0 picks a free port",
         "[ADDR:]PORT with a port in 0..65535", "off",
         [](RenderOptions& o, const OptionArg& a) {
             parse_serve_address(a.value); // checked now: a typo fails before the scene loads
             o.serve = a.value;
         },
         OptionRole::Local, nullptr},
        {"Output", "--display-server", nullptr, "HOST:PORT",
         "Send the image as it converges to the tev viewer listening at HOST:PORT (tev's own protocol, as pbrt-v4's "
         "--display-server; tev listens on 127.0.0.1:14158)",
         "HOST:PORT", "off", [](RenderOptions& o, const OptionArg& a) { o.display_server = non_empty(a); },
         OptionRole::Local, nullptr},
        {"Output", "--quiet", nullptr, nullptr, "No progress output", nullptr, nullptr,
         [](RenderOptions& o, const OptionArg&) { o.quiet = true; }, OptionRole::Local, nullptr},
        // 0 is refused, not read as "the camera's": leaving the option out says that.
        {"Image and camera", "--width", nullptr, "N", "Image width in pixels", "an integer in 1..16384",
         "the camera's aspect times the height",
         [](RenderOptions& o, const OptionArg& a) { o.settings.width = unsigned(parse_int(a, 1, 16384)); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.width; }},
        {"Image and camera", "--height", nullptr, "N", "Image height in pixels", "an integer in 1..16384",
         "512, or the width over the camera's aspect",
         [](RenderOptions& o, const OptionArg& a) { o.settings.height = unsigned(parse_int(a, 1, 16384)); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.height; }},
        {"Image and camera", "--variant", nullptr, "NAME",
         "Render the file's KHR_materials_variants variant NAME (the render lists the file's variants)",
         "a variant's name", "the file's default materials",
         [](RenderOptions& o, const OptionArg& a) { o.variant = non_empty(a); }, OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.variant; }},
        {"Image and camera", "--camera", nullptr, "N", "Index of the glTF camera to render through", "an integer >= 0",
         "0", [](RenderOptions& o, const OptionArg& a) { o.settings.camera = unsigned(parse_int(a, 0, INT_MAX)); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.camera; }},
        {"Image and camera", "--aperture", nullptr, "R", "Thin-lens aperture radius in scene units (depth of field)",
         "a finite number >= 0 (0 = pinhole)", "the camera's, else 0",
         [](RenderOptions& o, const OptionArg& a) {
             o.settings.aperture = parse_real(a, [](double x) { return x >= 0; });
         },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.aperture; }},
        {"Image and camera", "--focus-distance", nullptr, "D", "Distance to the plane in focus, in scene units",
         "a finite number > 0", "the camera's, else the scene centre's distance",
         [](RenderOptions& o, const OptionArg& a) {
             o.settings.focus_distance = parse_real(a, [](double x) { return x > 0; });
         },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.focus_distance; }},
        {"Image and camera", "--filter", nullptr, "NAME",
         "Pixel filter, importance-sampled: box = the pixel's square, tent = separable tent of radius 1 pixel",
         enum_range<PixelFilter>(), "box",
         [](RenderOptions& o, const OptionArg& a) { o.settings.filter = parse_enum<PixelFilter>(a); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return to_string(o.settings.filter); }},
        {"Integrator", "--integrator", nullptr, "NAME", integrator_help().c_str(), integrator_range().c_str(), "auto",
         [](RenderOptions& o, const OptionArg& a) {
             const std::string v = lower(a.value);
             if (v == "auto") o.settings.integrator = "auto";
             else if (is_integrator(v)) o.settings.integrator = integrator_row(v).name;
             else bad_value(a);
         },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.integrator; }},
        {"Integrator", "--passes", nullptr, "N", "Stop after N passes (with --time: whichever comes first)",
         "an integer >= 1 (0 = unlimited, with --time)", default_passes_text().c_str(),
         [](RenderOptions& o, const OptionArg& a) { o.passes = static_cast<uint64_t>(parse_int(a, 0, INT64_MAX)); },
         OptionRole::Run, [](const RenderOptions& o) -> Json { return o.passes ? Json(*o.passes) : Json("default"); }},
        {"Integrator", "--time", nullptr, "SECONDS", "Stop after this much render time", "a number of seconds > 0",
         "none",
         [](RenderOptions& o, const OptionArg& a) { o.time_limit = parse_real(a, [](double x) { return x > 0; }); },
         OptionRole::Run, [](const RenderOptions& o) -> Json { return o.time_limit; }},
        {"Integrator", "--photons", nullptr, "N", "Photons traced per pass (10000 in participating media unless given)",
         "an integer in 1..2147483647", "200000",
         [](RenderOptions& o, const OptionArg& a) {
             o.settings.photons = uint64_t(parse_int(a, 1, INT32_MAX));
             o.photons_given = true;
         },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.photons; }},
        // alpha of Hachisuka et al. 2008 (radius reduction): R^2 <- R^2 (N + alpha M) / (N + M).
        {"Integrator", "--alpha", nullptr, "A", "Fraction of new photons kept per pass (radius reduction)", "in (0, 1]",
         "0.7",
         [](RenderOptions& o, const OptionArg& a) {
             o.settings.alpha = parse_real(a, [](double x) { return x > 0 && x <= 1; });
         },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.alpha; }},
        {"Integrator", "--radius", nullptr, "R",
         "Initial gather radius R0 in scene units (and VCM's merging radius), at most the scene's bounding diameter",
         "a finite number > 0", "a heuristic from the pixels' footprints (docs/renderer.md)",
         [](RenderOptions& o, const OptionArg& a) {
             o.settings.radius = parse_real(a, [](double x) { return x > 0; });
         },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.radius; }},
        {"Integrator", "--spp", nullptr, "N", "Hit points (samples) per pixel per pass", "an integer in 1..256", "4",
         [](RenderOptions& o, const OptionArg& a) { o.settings.spp = unsigned(parse_int(a, 1, 256)); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.spp; }},
        {"Integrator", "--disc-coverage", nullptr, "MODE",
         "PPM, SPPM, PPPM: divide each gather by the part of its disc on its surface (no dark edges and corners)",
         enum_range<DiscCoverage>(), "auto",
         [](RenderOptions& o, const OptionArg& a) { o.settings.disc_coverage = parse_enum<DiscCoverage>(a); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return to_string(o.settings.disc_coverage); }},
        {"Integrator", "--volume-gather", nullptr, "MODE",
         "SPPM, PPPM in media: the camera rays' fog from points where they scatter, or from beams along them",
         enum_range<VolumeGather>(), "points",
         [](RenderOptions& o, const OptionArg& a) { o.settings.volume_gather = parse_enum<VolumeGather>(a); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return to_string(o.settings.volume_gather); }},
        {"Integrator", "--direct", nullptr, "MODE",
         "Direct light from photons (density estimate) or by sampling lights at hit points",
         enum_range<DirectLighting>(), "sample",
         [](RenderOptions& o, const OptionArg& a) { o.settings.direct = parse_enum<DirectLighting>(a); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return to_string(o.settings.direct); }},
        {"Integrator", "--max-bounces", nullptr, "N", "Longest eye or photon path", "an integer in 1..1024", "16",
         [](RenderOptions& o, const OptionArg& a) { o.settings.max_bounces = unsigned(parse_int(a, 1, 1024)); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.max_bounces; }},
        {"Integrator", "--sampler", nullptr, "NAME",
         "The path tracer's numbers: sobol = Owen-scrambled Sobol' points over each pixel's passes (lower error at "
         "equal time), zsobol = the same points laid out over the screen for the planned --passes, so that "
         "neighbouring pixels' errors cancel (needs a pass limit), independent = independent random streams; the "
         "other integrators draw independent ones",
         enum_range<Sampler>(), "sobol",
         [](RenderOptions& o, const OptionArg& a) { o.settings.sampler = parse_enum<Sampler>(a); }, OptionRole::Image,
         [](const RenderOptions& o) -> Json { return to_string(o.settings.sampler); }},
        {"Integrator", "--visual-importance", nullptr, nullptr,
         "PPM and SPPM: photon paths from Markov chains whose target is their visibility to the hit points "
         "(Hachisuka and Jensen 2009), so that photons go where the camera sees; for light that reaches what the "
         "camera sees through a gap or a window. One device",
         nullptr, nullptr, [](RenderOptions& o, const OptionArg&) { o.settings.visual_importance = true; },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.settings.visual_importance; }},
        {"Integrator", "--seed", nullptr, "S", "Random seed", "an integer in 0..18446744073709551615", "1",
         [](RenderOptions& o, const OptionArg& a) { o.settings.seed = parse_u64(a); }, OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.settings.seed; }},
        // Hachisuka, Jarosz and Jensen 2010: per-pixel bias and noise (integrators/error_estimate.h).
        {"Error estimation", "--target-error", nullptr, "E",
         "Stop once the estimated error is at most E: the 90th percentile over pixels of |L - L_true| / L, "
         "calibrated so that the actual error at the stop is between E/2 and E; --passes and --time still "
         "bound the render",
         "a number > 0", "none",
         [](RenderOptions& o, const OptionArg& a) { o.target_error = parse_real(a, [](double x) { return x > 0; }); },
         OptionRole::Run, [](const RenderOptions& o) -> Json { return o.target_error; }},
        {"Error estimation", "--error-bound", nullptr, nullptr,
         "With --target-error: stop on the conservative bound instead (the 90th percentile of per-pixel bounds "
         "that hold at --confidence; typically 3 to 4 times the actual error)",
         nullptr, nullptr, [](RenderOptions& o, const OptionArg&) { o.error_bound = true; }, OptionRole::Run,
         [](const RenderOptions& o) -> Json { return o.error_bound; }},
        {"Error estimation", "--confidence", nullptr, "P",
         "Confidence of the per-pixel error bounds (with --target-error or --error-output)", "in (0, 1)", "0.95",
         [](RenderOptions& o, const OptionArg& a) {
             o.confidence = parse_real(a, [](double x) { return x > 0 && x < 1; });
         },
         OptionRole::Run, [](const RenderOptions& o) -> Json { return confidence_of(o); }},
        {"Error estimation", "--error-output", nullptr, "FILE",
         "Write the per-pixel relative error bound to FILE (EXR) and a false-colour PNG beside it; the main "
         "EXR gets an \"error\" layer too",
         "a file name ending in .exr", "none",
         [](RenderOptions& o, const OptionArg& a) {
             if (!ends_with_ci(a.value, ".exr") || a.value.size() <= 4) bad_value(a);
             o.error_output = a.value;
         },
         OptionRole::Run, [](const RenderOptions& o) -> Json { return !o.error_output.empty(); }},
        {"Lighting", "--env", nullptr, "FILE",
         "Light the scene with an equirectangular environment map (top row +Y, centre -Z, u towards +X), or with "
         "the built-in studio environment (a soft key light and a rim light) for looking at a model",
         "an .exr or .hdr file, or studio (./studio for a file of that name)", "none",
         [](RenderOptions& o, const OptionArg& a) { o.env.file = non_empty(a); }, OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.env.file; }},
        {"Lighting", "--env-color", nullptr, "R,G,B", "Light the scene with a uniform environment of this radiance",
         "three numbers >= 0, comma-separated", "none",
         [](RenderOptions& o, const OptionArg& a) {
             o.env.color = parse_rgb(a);
             o.env.has_color = true;
         },
         OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.env.has_color ? Json(o.env.color) : Json(); }},
        {"Lighting", "--env-strength", nullptr, "S", "Scale the environment (also the default one)",
         "a finite number >= 0", "1",
         [](RenderOptions& o, const OptionArg& a) { o.env.strength = parse_real(a, [](double x) { return x >= 0; }); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.env.strength; }},
        {"Lighting", "--env-rotate", nullptr, "DEG", "Turn the environment about +Y (right-handed: +X towards -Z)",
         "a finite number of degrees", "0",
         [](RenderOptions& o, const OptionArg& a) {
             o.env.rotate_degrees = parse_real(a, [](double) { return true; });
         },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.env.rotate_degrees; }},
        {"Lighting", "--env-hidden", nullptr, nullptr,
         "Camera rays that leave the scene see black; the environment still lights it", nullptr, nullptr,
         [](RenderOptions& o, const OptionArg&) { o.env.hidden = true; }, OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.env.hidden; }},
        {"Lighting", "--no-default-light", nullptr, nullptr,
         "No default environment: a scene without a world of its own is lit by its own lights alone (refused if it has "
         "none)",
         nullptr, nullptr, [](RenderOptions& o, const OptionArg&) { o.env.default_light = false; }, OptionRole::Image,
         [](const RenderOptions& o) -> Json { return !o.env.default_light; }},
        {"Medium", "--medium-density", nullptr, "D",
         "Fill the world outside closed volumes with a homogeneous medium of extinction D per scene unit (the camera "
         "in it), or set the density of the file's (extras.clppm_medium)",
         "a number >= 0, or R,G,B", "the file's, else none",
         [](RenderOptions& o, const OptionArg& a) {
             o.medium.density = parse_rgb_or_number(a);
             o.medium.has_density = true;
         },
         OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.medium.has_density ? Json(o.medium.density) : Json(); }},
        {"Medium", "--medium-albedo", nullptr, "A",
         "The medium's single-scattering albedo: the part of what it stops that it scatters (the rest it absorbs)",
         "a number from 0 to 1, or R,G,B", "the file's, else 1",
         [](RenderOptions& o, const OptionArg& a) {
             o.medium.albedo = parse_rgb_or_number(a);
             for (float x : o.medium.albedo)
                 if (x > 1.f) bad_value(a);
             o.medium.has_albedo = true;
         },
         OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.medium.has_albedo ? Json(o.medium.albedo) : Json(); }},
        {"Medium", "--medium-anisotropy", nullptr, "G",
         "The medium's Henyey-Greenstein g: > 0 scatters forwards, < 0 backwards, 0 alike in every direction",
         "a number above -1 and below 1", "the file's, else 0",
         [](RenderOptions& o, const OptionArg& a) {
             o.medium.anisotropy = float(parse_real(a, [](double g) { return g > -1 && g < 1; }));
             o.medium.has_anisotropy = true;
         },
         OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.medium.has_anisotropy ? Json(o.medium.anisotropy) : Json(); }},
        {"Medium", "--medium-scale", nullptr, "S", "Scale the medium's density (the file's or --medium-density)",
         "a finite number >= 0", "1",
         [](RenderOptions& o, const OptionArg& a) { o.medium.scale = parse_real(a, [](double x) { return x >= 0; }); },
         OptionRole::Image, [](const RenderOptions& o) -> Json { return o.medium.scale; }},
        {"Medium", "--no-medium", nullptr, nullptr, "Render without the file's medium (extras.clppm_medium)", nullptr,
         nullptr, [](RenderOptions& o, const OptionArg&) { o.medium.none = true; }, OptionRole::Image,
         [](const RenderOptions& o) -> Json { return o.medium.none; }},
        {"Checkpoints", "--checkpoint", nullptr, "FILE",
         "Save the complete progressive state to FILE (atomically) periodically, on Ctrl-C and at the end",
         "a file name", "none", [](RenderOptions& o, const OptionArg& a) { o.checkpoint = non_empty(a); },
         OptionRole::Local, nullptr},
        {"Checkpoints", "--checkpoint-every", nullptr, "K", "Save the checkpoint every K passes",
         "an integer >= 0 (0 = off)", "0",
         [](RenderOptions& o,
            const OptionArg& a) { o.checkpoint_every = static_cast<uint64_t>(parse_int(a, 0, INT64_MAX)); },
         OptionRole::Local, nullptr},
        {"Checkpoints", "--checkpoint-interval", nullptr, "SECONDS", "Save the checkpoint every SECONDS of rendering",
         "a number of seconds > 0", "300",
         [](RenderOptions& o,
            const OptionArg& a) { o.checkpoint_interval = parse_real(a, [](double x) { return x > 0; }); },
         OptionRole::Local, nullptr},
        {"Checkpoints", "--resume", nullptr, "FILE",
         "Continue the render saved in checkpoint FILE (same scene and image-shaping options; --passes "
         "counts from the start of the original render, --time this run only)",
         "a checkpoint file", "none", [](RenderOptions& o, const OptionArg& a) { o.resume = non_empty(a); },
         OptionRole::Run, [](const RenderOptions& o) -> Json { return o.resume; }},
        {"Devices and kernels", "--device", nullptr, "SPEC", "Device to render on; repeatable (see --list-devices)",
         "a device index, cpu, gpu, auto (the fastest, measured), or part of an implementation's name (pocl, "
         "intel, nvidia) or a device's",
         "automatic", [](RenderOptions& o, const OptionArg& a) { o.devices.push_back(non_empty(a)); },
         OptionRole::Local, nullptr},
        {"Devices and kernels", "--generic-kernels", nullptr, nullptr,
         "Build the generic kernels instead of ones specialised for the scene's materials, lights and camera", nullptr,
         nullptr, [](RenderOptions& o, const OptionArg&) { o.generic_kernels = true; }, OptionRole::Run,
         [](const RenderOptions& o) -> Json { return o.generic_kernels; }},
        {"Devices and kernels", "--kernel-dir", nullptr, "DIR", "Load kernels from DIR instead of the embedded copies",
         "a directory", "embedded", [](RenderOptions& o, const OptionArg& a) { o.kernel_dir = non_empty(a); },
         OptionRole::Run, [](const RenderOptions& o) -> Json { return o.kernel_dir; }},
        {"Devices and kernels", "--dump-kernel-source", nullptr, "FILE",
         "Write the assembled kernel source and build options to FILE", "a file name", "none",
         [](RenderOptions& o, const OptionArg& a) { o.dump_kernel_source = non_empty(a); }, OptionRole::Local, nullptr},
    };
    return table;
}

Json option_values(const RenderOptions& options, OptionRole role) {
    Json out = Json::object();
    for (const RenderOptionSpec& s : render_option_table())
        if (s.role == role) out[s.name] = s.value(options);
    return out;
}

const RenderOptionSpec* find_render_option(const std::string& name) {
    for (const RenderOptionSpec& spec : render_option_table())
        if (name == spec.name || (spec.short_name && name == spec.short_name)) return &spec;
    return nullptr;
}

void apply_render_option(RenderOptions& options, const RenderOptionSpec& spec, const std::string& shown,
                         const std::string& value) {
    spec.apply(options, OptionArg{shown, value, spec.range});
}

void check_render_options(const RenderOptions& o) {
    if (o.passes && *o.passes == 0 && !(o.time_limit > 0)) throw Error("--passes 0: unlimited passes need --time");
    if (o.error_bound && !(o.target_error > 0)) throw Error("--error-bound: needs --target-error");
    if (o.confidence && !wants_error_estimate(o)) throw Error("--confidence: needs --target-error or --error-output");
    if (o.progressive_output > 0 && o.output.empty()) throw Error("--progressive-output: needs an output image");
    if (o.settings.visual_importance &&
        (o.settings.integrator == "auto" || !integrator_row(o.settings.integrator).visual_importance))
        throw Error("--visual-importance: needs --integrator " + visual_importance_integrators() +
                    " (photon paths that the chains guide)");
}

} // namespace clppm
