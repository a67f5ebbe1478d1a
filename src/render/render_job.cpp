#include "render/render_job.h"

#include <cstdio>

#include "device/cluster.h"
#include "integrators/default_integrator.h"
#include "integrators/memory_estimate.h"
#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "io/image_io.h"
#include "io/output_lock.h"
#include "render/device_auto.h"
#include "render/device_choice.h"
#include "render/job_fingerprint.h"
#include "render/rank_agreement.h"
#include "scene/environment.h"
#include "scene/gltf/gltf_load.h"
#include "scene/medium.h"
#include "scene/scene_features.h"
#include "scene/scene_fingerprint.h"
#include "util/error.h"
#include "util/steady_seconds.h"
#include "util/version.h"

namespace clppm {

namespace {

std::string number(const char* format, double x) {
    char s[64];
    std::snprintf(s, sizeof s, format, x);
    return s;
}

} // namespace

RenderJob::RenderJob(const RenderOptions& options, RenderLog& log)
    : options_(options), log_(log), writer_(cluster().rank() == 0), created_s_(steady_seconds()) {
    require_ranks_agree(options_every_rank_shares(options_)); // before anything can fail on one rank alone
    const KernelDirScope kernels(options_.kernel_dir);        // this render's, not the process's
    const std::vector<DeviceInfo> devices = list_devices();
    const std::vector<DeviceInfo> chosen = wants_auto_device(options_.devices)
                                               ? std::vector<DeviceInfo>{auto_device(options_, devices, log_)}
                                               : choose_devices(options_.devices, devices);
    if (writer_) {
        // Every file the render will write is checked before hours of rendering, not after, and
        // two renders writing the same files would mix their outputs: the second is refused.
        const std::vector<std::string> files = output_files(options_);
        for (const std::string& f : files) check_writable(f);
        lock_ = std::make_unique<OutputLock>(files);
    }
    load_scene();
    choose_integrator(chosen.size());
    set_up_device(chosen);
    build_kernels(chosen);
    start_s_ = steady_seconds();
    integ_->prepare();
    if (!options_.resume.empty()) resume();
}

RenderJob::~RenderJob() = default;

void RenderJob::load_scene() {
    if (options_.scene.empty() && !options_.variant.empty())
        throw Error("--variant " + options_.variant + ": the built-in scene has no material variants");
    scene_ = options_.scene.empty() ? load_default_scene() : load_gltf(options_.scene, options_.variant);
    if (!scene_.variants.empty()) {
        std::string names;
        for (const std::string& n : scene_.variants) names += (names.empty() ? "" : ", ") + n;
        variant_note_ = "material variants: " + names + "; rendering " +
                        (scene_.variant.empty() ? "the file's default materials (--variant NAME for one)"
                                                : "variant " + scene_.variant);
    }
    for (const std::string& w : scene_.warnings) log_.warn(scene_.source + ": " + w);
    if (scene_.degenerate_triangles_skipped)
        log_.warn(scene_.source + ": skipped " + std::to_string(scene_.degenerate_triangles_skipped) +
                  " degenerate triangle(s)");
    if (scene_.meshes_without_normals)
        log_.note(scene_.source + ": computed normals for " + std::to_string(scene_.meshes_without_normals) +
                  " primitive(s) without normals");
    apply_environment(scene_, options_.env, &world_note_); // said once the render is set up
    apply_medium(scene_, options_.medium, &medium_note_);
    scene_hash_ = scene_fingerprint(scene_);
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(scene_hash_));
    require_ranks_agree({{"the scene's contents (" + scene_.source + ")", hash}}); // the same file everywhere
}

void RenderJob::choose_integrator(size_t devices) {
    RenderSettings& s = options_.settings;
    if (s.integrator == "auto") {
        const bool chains_allowed = !cluster().distributed() && devices == 1;
        const IntegratorChoice choice = default_integrator(scene_, s, chains_allowed);
        s.integrator = choice.integrator;
        s.visual_importance = choice.visual_importance;
        integrator_note_ = "integrator " + s.integrator + ": " + choice.reason;
    }
    row_ = &integrator_row(s.integrator);
    s.integrator = row_->name;
    require_media_support(*row_, scene_has_media(scene_), s.volume_gather);
    if (row_->unit == WorkUnit::Photons && scene_has_media(scene_) && !options_.photons_given) {
        s.photons = kMediaPhotonsPerPass;
        photons_note_ = "photons: " + std::to_string(s.photons) +
                        " per pass in participating media, where each collision stores one (--photons to choose)";
    }
    if (s.filter == PixelFilter::Tent && !row_->tent_filter)
        throw Error(std::string("--integrator ") + row_->name +
                    ": light tracing splats with the box filter only; drop --filter tent");
}

// Refuses a render the device cannot hold before allocating anything, then uploads the scene and
// refuses a lens or a gather radius the scene makes meaningless.
void RenderJob::set_up_device(const std::vector<DeviceInfo>& chosen) {
    const DeviceInfo& info = chosen.front();
    const RenderSettings& s = options_.settings;
    const ImageResolution res = image_resolution(scene_, s);
    check_memory_fits(estimate_memory(scene_, s, res.width, res.height, info, wants_error_estimate(options_)), info);
    dc_ = std::make_unique<DeviceContext>(info);
    ds_ = std::make_unique<DeviceScene>(upload_scene(*dc_, scene_, s));
    for (const std::string& n : ds_->notes) log_.note(n);
    for (const std::string& w : ds_->warnings) log_.warn(scene_.source + ": " + w);
    // A gather radius beyond the scene gathers every photon everywhere, and an infinite one would
    // never end; a lens wider than the scene images nothing (every ray from it misses or grazes
    // the scene, and floats lose the scene's detail at the lens's scale). Both are refused, naming
    // the scene's size.
    const double diameter = 2.0 * double(ds_->info.radius);
    if (s.radius > diameter)
        throw Error("--radius " + number("%g", s.radius) + ": larger than the scene's bounding diameter " +
                    number("%g", diameter) + " (" + scene_.source + ")");
    const double lens = double(ds_->camera.lens_radius);
    if (lens > diameter)
        throw Error((s.aperture >= 0 ? "--aperture " + number("%g", s.aperture)
                                     : "camera " + std::to_string(s.camera) + "'s aperture " + number("%g", lens)) +
                    ": larger than the scene's bounding diameter " + number("%g", diameter) + " (" + scene_.source +
                    "): no image forms through such a lens");
    options_.settings.width = ds_->camera.width;
    options_.settings.height = ds_->camera.height;
}

void RenderJob::build_kernels(const std::vector<DeviceInfo>& chosen) {
    const RenderSettings& s = options_.settings;
    const SceneFeatures features = scene_features(scene_, *ds_);
    const std::string build_options = integrator_build_options(
        s, dc_->info, options_.generic_kernels ? std::string() : feature_build_options(features));
    const std::string source = assemble_kernel_source(row_->program_file);
    if (!options_.dump_kernel_source.empty())
        write_file_atomic(options_.dump_kernel_source, "// build options: " + build_options + "\n" + source);
    fingerprint_ = job_fingerprint(options_, *ds_, scene_hash_, source + build_options);
    program_ = build_program(*dc_, row_->program_file, build_options, &build_);
    log_.note("device [" + std::to_string(dc_->info.index) + "] " + dc_->info.name + ", " +
              std::to_string(ds_->camera.width) + "x" + std::to_string(ds_->camera.height) + ", " +
              std::to_string(ds_->num_triangles) + " triangles, " + std::to_string(ds_->lights.size()) +
              " lights, kernels " +
              (options_.generic_kernels ? std::string("generic") : "for " + describe_features(features)) + " " +
              (build_.from_cache ? "cached" : "built") + " in " + number("%.3f", build_.seconds) + " s" +
              (build_.driver_cache ? " (the driver's cache)" : ""));
    if (!world_note_.empty()) log_.note(world_note_);
    if (!medium_note_.empty()) log_.note(medium_note_);
    if (!variant_note_.empty()) log_.note(variant_note_);
    if (!integrator_note_.empty()) log_.note(integrator_note_);
    if (!photons_note_.empty()) log_.note(photons_note_);
    const char* unit = row_->unit == WorkUnit::Photons ? "photons" : "pixels";
    if (cluster().distributed())
        log_.note(std::to_string(cluster().size()) + " processes (MPI): each pass's " + unit +
                  " are shared in proportion to each one's measured speed, their sums combined exactly" +
                  row_->mpi_note);
    if (row_->warnings)
        for (const std::string& w : row_->warnings(scene_, features)) log_.warn(w);
    SecondaryDevices secondaries{std::vector<DeviceInfo>(chosen.begin() + 1, chosen.end()), row_->program_file,
                                 build_options};
    if (!secondaries.devices.empty() && !row_->several_devices) {
        log_.warn(std::string("the ") + row_->name + " integrator renders on the first device only");
        secondaries.devices.clear();
    }
    for (const DeviceInfo& d : secondaries.devices) {
        integrator_build_options(s, d); // the same requirements (fp64) as the primary
        log_.note(std::string("sharing ") + unit + " with device [" + std::to_string(d.index) + "] " + d.name);
    }
    options_.settings.planned_passes = pass_limit();
    integ_ = make_integrator(*dc_, *ds_, s, program_, secondaries);
    if (wants_error_estimate(options_)) {
        const char* asked = options_.target_error > 0 ? "--target-error" : "--error-output";
        if (!secondaries.devices.empty())
            throw Error(std::string(asked) + ": error estimation runs on one device; give a single --device");
        if (!row_->estimates_error)
            throw Error(std::string(asked) + ": the " + integ_->name() + " integrator does not estimate its error");
        integ_->enable_error_estimation();
        estimating_ = true;
    }
}

void RenderJob::resume() {
    const Checkpoint ck = open_resume(options_.resume, fingerprint_);
    const std::string here = dc_->info.name + " / " + dc_->info.driver_version;
    if (ck.header.value("device", std::string()) != here)
        log_.warn("resuming on another device than the checkpoint's (" +
                  ck.header.value("device", std::string("unknown")) + "): the image will not be bit-identical");
    integ_->restore(ck);
    resumed_at_ = passes();
    log_.note("resumed " + options_.resume + " at pass " + std::to_string(resumed_at_));
    const uint64_t limit = pass_limit();
    if (limit > 0 && resumed_at_ >= limit)
        log_.warn("--passes " + std::to_string(limit) + ": the checkpoint already holds " +
                  std::to_string(resumed_at_) +
                  " passes (--passes counts from the start of the original render); nothing to render");
}

void RenderJob::run_pass(uint64_t max_passes) {
    integ_->allow_passes(max_passes);
    integ_->run_pass();
    if (!estimating_) return;
    error_ = integ_->error_estimate(confidence_of(options_));
    trend_.add(passes(), render_seconds(), error_measure());
}

uint64_t RenderJob::pass_limit() const { return clppm::pass_limit(options_, row_->default_passes); }

double RenderJob::render_seconds() const { return steady_seconds() - start_s_; }

int RenderJob::width() const { return int(ds_->camera.width); }

int RenderJob::height() const { return int(ds_->camera.height); }

double RenderJob::error_measure() const { return options_.error_bound ? error_.image_error : error_.expected_error; }

bool RenderJob::error_target_reached() const {
    return estimating_ && options_.target_error > 0 && error_.passes >= kMinPassesToStop &&
           error_measure() <= options_.target_error;
}

double RenderJob::error_eta() const { return trend_.eta_seconds(options_.target_error); }

Image RenderJob::image(bool interrupted) const {
    Image img = integ_->image();
    img.attributes["clppm:version"] = kVersion;
    img.attributes["clppm:integrator"] = integ_->name();
    img.attributes["clppm:passes"] = std::to_string(passes());
    img.attributes["clppm:interrupted"] = interrupted ? "yes" : "no";
    if (options_.write_png) {
        img.attributes["clppm:png_tonemap"] = to_string(options_.tone.curve);
        img.attributes["clppm:png_exposure_ev"] = number("%.6g", applied_exposure_ev(options_.tone, img));
    }
    return img;
}

void RenderJob::save_images(const std::string& exr_path, bool png, bool interrupted) const {
    save_images(exr_path, png, image(interrupted));
}

void RenderJob::save_images(const std::string& exr_path, bool png, const Image& img) const {
    std::vector<ExrLayer> layers;
    if (estimating_ && error_.relative.size() == img.rgb.size() / 3) layers.push_back({"error", &error_.relative});
    write_exr(exr_path, img, layers);
    if (png) write_png(png_path_for(exr_path), img, options_.tone);
}

void RenderJob::save_outputs(bool interrupted) const { save_outputs(image(interrupted)); }

void RenderJob::save_outputs(const Image& img) const {
    if (!options_.output.empty()) save_images(options_.output, options_.write_png, img);
    if (options_.error_output.empty() || error_.relative.empty()) return;
    // The relative bound as a grey EXR (its bias and noise parts as layers) and a false-colour
    // PNG, red at twice the target (0.2 without one).
    Image grey;
    grey.width = error_.width, grey.height = error_.height;
    grey.rgb.reserve(error_.relative.size() * 3);
    for (float v : error_.relative) grey.rgb.insert(grey.rgb.end(), {v, v, v});
    const std::vector<float> bias = relative_bounds(error_.bias, error_.luminance),
                             noise = relative_bounds(error_.noise, error_.luminance);
    write_exr(options_.error_output, grey, {{"bias", &bias}, {"noise", &noise}});
    const double scale = options_.target_error > 0 ? 2 * options_.target_error : 0.2;
    write_png(png_path_for(options_.error_output), false_colour(error_.relative, error_.width, error_.height, scale));
}

void RenderJob::save_checkpoint() const {
    Checkpoint ck;
    ck.header["version"] = kVersion;
    ck.header["fingerprint"] = fingerprint_;
    ck.header["device"] = dc_->info.name + " / " + dc_->info.driver_version;
    integ_->save(ck);
    write_checkpoint(options_.checkpoint, ck);
}

Json RenderJob::stats_json(const RenderEnd& end, const Image* given) const {
    const IntegratorStats& st = integ_->stats();
    const Image img = given ? *given : image(end.interrupted);
    const double render_s = end.render_seconds;
    Json j;
    j["version"] = kVersion;
    j["scene"] = scene_.source;
    j["integrator"] = integ_->name();
    j["direct"] = to_string(options_.settings.direct);
    // Every option that shapes the image or says when the render stops, as the option table reads it.
    j["options"] = options_every_rank_shares(options_);
    j["options"].erase("SCENE");
    j["device"] = {{"index", dc_->info.index},
                   {"name", dc_->info.name},
                   {"platform", dc_->info.platform_name},
                   {"type", dc_->info.type_name()},
                   {"driver", dc_->info.driver_version}};
    j["width"] = ds_->camera.width;
    j["height"] = ds_->camera.height;
    j["passes"] = st.passes;
    j["photons_per_pass"] = options_.settings.photons;
    j["photons_emitted"] = st.photons_emitted;
    j["photons_stored"] = st.photons_stored;
    j["hitpoints"] = st.hitpoints;
    j["alpha"] = options_.settings.alpha;
    j["seed"] = options_.settings.seed;
    j["initial_radius"] = st.initial_radius;
    j["mean_radius"] = st.mean_radius;
    if (st.initial_volume_radius > 0) {
        j["initial_volume_radius"] = st.initial_volume_radius;
        j["volume_radius"] = st.volume_radius;
    }
    j["render_seconds"] = render_s;
    j["total_seconds"] = steady_seconds() - created_s_;
    j["passes_per_second"] = render_s > 0 ? double(st.passes) / render_s : 0.0;
    j["photons_per_second"] = render_s > 0 ? double(st.photons_emitted) / render_s : 0.0;
    Json phases = Json::object();
    for (const auto& [k, v] : st.phase_seconds) phases[k] = v;
    j["phase_seconds"] = phases;
    j["kernel_build"] = {{"seconds", build_.seconds},
                         {"from_cache", build_.from_cache},
                         {"driver_cache", build_.driver_cache},
                         {"options", build_.options}};
    j["bvh"] = {
        {"build_seconds", ds_->bvh_build_seconds}, {"nodes", ds_->bvh_nodes}, {"triangles", ds_->num_triangles}};
    j["lights"] = ds_->lights.size();
    j["device_memory_bytes"] = {{"scene", ds_->device_bytes},
                                {"integrator", st.device_bytes},
                                {"photons", st.photon_bytes},
                                {"total", ds_->device_bytes + st.device_bytes + st.photon_bytes}};
    j["photon_batches_per_pass"] = st.photon_batches;
    if (st.pass_launches > 0) j["pass_launches"] = st.pass_launches;
    if (options_.settings.visual_importance) {
        const uint64_t* c = st.chain_counts;
        j["visual_importance"] = {
            {"uniform_visible_fraction",
             st.photons_emitted ? double(c[CHAIN_UNIFORM_VISIBLE]) / double(st.photons_emitted) : 0.0},
            {"states_deposited", c[CHAIN_STATES]},
            {"mutation_acceptance", c[CHAIN_MUTATIONS] ? double(c[CHAIN_ACCEPTED]) / double(c[CHAIN_MUTATIONS]) : 0.0},
            {"mutations", c[CHAIN_MUTATIONS]}};
    }
    j["device_photons_last_pass"] = st.device_photons;
    j["degenerate_triangles_skipped"] = scene_.degenerate_triangles_skipped;
    j["nonfinite_pixels"] = count_nonfinite(img);
    j["negative_pixels"] = count_negative(img);
    j["mean_radiance"] = mean_radiance(img);
    j["interrupted"] = end.interrupted;
    if (estimating_)
        j["error"] = {{"estimated", error_.expected_error}, {"bound", error_.image_error},
                      {"target", options_.target_error},    {"stops_on", options_.error_bound ? "bound" : "estimate"},
                      {"reached", error_target_reached()},  {"confidence", confidence_of(options_)},
                      {"percentile", kErrorPercentile},     {"passes", error_.passes}};
    return j;
}

} // namespace clppm
