#include "cli/render_session.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/default_integrator.h"
#include "cli/interrupt.h"
#include "cli/live_view.h"
#include "cli/progress.h"
#include "cli/tev_client.h"
#include "device/cluster.h"
#include "device/device.h"
#include "device/kernel_program.h"
#include "integrators/error_estimate.h"
#include "integrators/integrator.h"
#include "integrators/integrator_factory.h"
#include "integrators/memory_estimate.h"
#include "io/checkpoint.h"
#include "io/image_io.h"
#include "io/output_lock.h"
#include "io/stats_json.h"
#include "scene/device_scene.h"
#include "scene/environment.h"
#include "scene/gltf/gltf_load.h"
#include "scene/scene_features.h"
#include "scene/scene_fingerprint.h"
#include "util/cancellation.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/version.h"

namespace clppm {

namespace {

struct Clock {
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }
};

// What clppm is doing: --quiet hides it.
void note(const Options& opt, const std::string& msg) {
    if (!opt.quiet) std::fprintf(stderr, "clppm: %s\n", msg.c_str());
}

// What the user must know about the result: always shown, --quiet or not; by rank 0 alone when
// several processes render (the others see the same).
void warn(const std::string& msg) {
    if (cluster().rank() == 0) std::fprintf(stderr, "clppm: warning: %s\n", msg.c_str());
}

// o.integrator is settled by now (--integrator, or default_integrator's choice).
RenderSettings settings_from(const Options& o) {
    RenderSettings s;
    s.integrator = o.integrator;
    s.direct = o.direct;
    s.width = unsigned(o.width);
    s.height = unsigned(o.height);
    s.camera = unsigned(o.camera);
    s.spp = unsigned(o.spp);
    s.photons = o.photons_per_pass;
    s.alpha = o.alpha;
    s.radius = o.radius;
    s.seed = o.seed;
    s.max_bounces = unsigned(o.max_bounces);
    s.aperture = o.aperture;
    s.focus_distance = o.focus_distance;
    s.filter = o.filter;
    return s;
}

// The devices a render runs on, the first of them primary: every --device spec in order ("all":
// every device), else the first GPU, else device 0. A device named twice is an error.
std::vector<DeviceInfo> choose_devices(const Options& opt, const std::vector<DeviceInfo>& devices) {
    std::vector<DeviceInfo> chosen;
    for (const std::string& spec : opt.devices) {
        if (spec == "all") {
            if (devices.empty()) select_device(devices, spec); // throws: no device
            for (const DeviceInfo& d : devices) chosen.push_back(d);
            continue;
        }
        const DeviceInfo& d = select_device(devices, spec);
        for (const DeviceInfo& c : chosen)
            if (c.index == d.index)
                throw Error("--device " + spec + ": device [" + std::to_string(d.index) + "] " + d.name +
                            " is given twice");
        chosen.push_back(d);
    }
    if (!chosen.empty()) return chosen;
    for (const DeviceInfo& d : devices)
        if (d.type & CL_DEVICE_TYPE_GPU) return {d};
    return {select_device(devices, "0")};
}

// Every file the render will write is checked before hours of rendering, not after.
void check_outputs(const Options& opt) {
    check_writable(opt.output);
    if (opt.write_png) check_writable(png_path_for(opt.output));
    if (!opt.stats_json.empty()) check_writable(opt.stats_json);
    if (!opt.checkpoint.empty()) check_writable(opt.checkpoint);
    if (!opt.error_output.empty()) {
        check_writable(opt.error_output);
        check_writable(png_path_for(opt.error_output));
    }
}

// --target-error / --error-output: the estimate after every pass, for halting and the outputs.
struct ErrorTracking {
    IntegratorBase* integ = nullptr; // null: not estimating
    ErrorImage last;
    ErrorTrend trend;

    // The estimate --target-error halts on: the calibrated one, or with --error-bound the bound.
    static double measure(const Options& opt, const ErrorImage& e) {
        return opt.error_bound ? e.image_error : e.expected_error;
    }
    void update(const Options& opt, Progress& progress, uint64_t pass, double seconds) {
        if (!integ) return;
        last = integ->error_estimate(opt.confidence);
        trend.add(pass, seconds, measure(opt, last));
        progress.set_error(measure(opt, last), opt.target_error, trend.eta_seconds(opt.target_error));
    }
    // Not before kMinPassesToStop passes: the spread of fewer says little.
    bool reached(const Options& opt) const {
        return integ && opt.target_error > 0 && last.passes >= kMinPassesToStop &&
               measure(opt, last) <= opt.target_error;
    }
};

// The integrator's image, with the EXR header attributes that say how it came to be (as the stats
// JSON does): version, integrator, passes, whether the render was interrupted, and the tone curve
// and exposure the PNG beside it applied (the EXR itself is linear).
Image current_image(const Options& opt, IntegratorBase& integ, int signal) {
    Image img = integ.image();
    img.attributes["clppm:version"] = kVersion;
    img.attributes["clppm:integrator"] = integ.name();
    img.attributes["clppm:passes"] = std::to_string(integ.stats().passes);
    img.attributes["clppm:interrupted"] = signal ? "yes" : "no";
    if (opt.write_png) {
        char ev[32];
        std::snprintf(ev, sizeof ev, "%.6g", applied_exposure_ev(opt.tone, img));
        img.attributes["clppm:png_tonemap"] = to_string(opt.tone.curve);
        img.attributes["clppm:png_exposure_ev"] = ev;
    }
    return img;
}

// The main images, with the per-pixel relative error bound as an "error" layer when estimating.
void save_images(const Options& opt, const Image& img, const ErrorTracking& errors) {
    std::vector<ExrLayer> layers;
    if (errors.integ && errors.last.relative.size() == img.rgb.size() / 3)
        layers.push_back({"error", &errors.last.relative});
    write_exr(opt.output, img, layers);
    if (opt.write_png) write_png(png_path_for(opt.output), img, opt.tone);
}

// --error-output: the relative bound as a grey EXR (with its bias and noise parts as layers) and a
// false-colour PNG, red at twice the target (0.2 without one).
void save_error_images(const Options& opt, const ErrorImage& e) {
    Image grey;
    grey.width = e.width, grey.height = e.height;
    grey.rgb.reserve(e.relative.size() * 3);
    for (float v : e.relative) grey.rgb.insert(grey.rgb.end(), {v, v, v});
    const std::vector<float> bias = relative_bounds(e.bias, e.luminance), noise = relative_bounds(e.noise, e.luminance);
    write_exr(opt.error_output, grey, {{"bias", &bias}, {"noise", &noise}});
    const double scale = opt.target_error > 0 ? 2 * opt.target_error : 0.2;
    write_png(png_path_for(opt.error_output), false_colour(e.relative, e.width, e.height, scale));
}

// Whether some material is smooth glass or a mirror (roughness below 0.01, where kernels/bsdf.cl
// makes the lobe a delta): light from a delta light by way of it is a path the path tracer never
// samples.
bool has_smooth_glass_or_mirror(const Scene& scene) {
    for (const dev::Material& m : scene.materials)
        if (m.roughness < 0.01f && (m.metallic > 0.f || m.transmission > 0.f)) return true;
    return false;
}

// What a checkpoint must agree on to be resumed: everything that shapes the image.
Json image_fingerprint(const Options& o, const RenderSettings& settings, const DeviceScene& ds, uint64_t scene_hash,
                       const std::string& kernel_source) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(scene_hash));
    char khex[17];
    std::snprintf(khex, sizeof khex, "%016llx", fnv1a64(kernel_source));
    Json j;
    j["scene"] = hex;
    j["kernels"] = khex;
    j["--integrator"] = to_string(settings.integrator);
    j["--direct"] = to_string(o.direct);
    j["--width"] = ds.camera.width;
    j["--height"] = ds.camera.height;
    j["--camera"] = o.camera;
    j["--spp"] = o.spp;
    j["--photons"] = o.photons_per_pass;
    j["--alpha"] = o.alpha;
    j["--radius"] = o.radius;
    j["--seed"] = o.seed;
    j["--max-bounces"] = o.max_bounces;
    j["--filter"] = to_string(o.filter);
    j["--aperture"] = o.aperture;
    j["--focus-distance"] = o.focus_distance;
    return j;
}

Json make_stats(const Options& opt, const DeviceContext& dc, const DeviceScene& ds, const Scene& scene,
                const IntegratorBase& integ, const ProgramBuildStats& build, double render_s, double total_s,
                const Image& img, int signal) {
    const IntegratorStats& st = integ.stats();
    Json j;
    j["version"] = kVersion;
    j["scene"] = scene.source;
    j["integrator"] = integ.name();
    j["direct"] = to_string(opt.direct);
    j["device"] = {{"index", dc.info.index},
                   {"name", dc.info.name},
                   {"platform", dc.info.platform_name},
                   {"type", dc.info.type_name()},
                   {"driver", dc.info.driver_version}};
    j["width"] = ds.camera.width;
    j["height"] = ds.camera.height;
    j["passes"] = st.passes;
    j["photons_per_pass"] = opt.photons_per_pass;
    j["photons_emitted"] = st.photons_emitted;
    j["photons_stored"] = st.photons_stored;
    j["hitpoints"] = st.hitpoints;
    j["alpha"] = opt.alpha;
    j["seed"] = opt.seed;
    j["initial_radius"] = st.initial_radius;
    j["mean_radius"] = st.mean_radius;
    j["render_seconds"] = render_s;
    j["total_seconds"] = total_s;
    j["passes_per_second"] = render_s > 0 ? double(st.passes) / render_s : 0.0;
    j["photons_per_second"] = render_s > 0 ? double(st.photons_emitted) / render_s : 0.0;
    Json phases = Json::object();
    for (const auto& [k, v] : st.phase_seconds) phases[k] = v;
    j["phase_seconds"] = phases;
    j["kernel_build"] = {{"seconds", build.seconds},
                         {"from_cache", build.from_cache},
                         {"driver_cache", build.driver_cache},
                         {"options", build.options}};
    j["bvh"] = {{"build_seconds", ds.bvh_build_seconds}, {"nodes", ds.bvh_nodes}, {"triangles", ds.num_triangles}};
    j["lights"] = ds.lights.size();
    j["device_memory_bytes"] = {{"scene", ds.device_bytes},
                                {"integrator", st.device_bytes},
                                {"photons", st.photon_bytes},
                                {"total", ds.device_bytes + st.device_bytes + st.photon_bytes}};
    j["photon_batches_per_pass"] = st.photon_batches;
    j["device_photons_last_pass"] = st.device_photons;
    j["degenerate_triangles_skipped"] = scene.degenerate_triangles_skipped;
    j["nonfinite_pixels"] = count_nonfinite(img);
    j["negative_pixels"] = count_negative(img);
    j["mean_radiance"] = mean_radiance(img);
    j["interrupted"] = signal != 0;
    return j;
}

Scene load_scene(const Options& opt) {
    Scene scene = opt.scene.empty() ? load_default_scene() : load_gltf(opt.scene);
    for (const std::string& w : scene.warnings) warn(scene.source + ": " + w);
    if (scene.degenerate_triangles_skipped)
        warn(scene.source + ": skipped " + std::to_string(scene.degenerate_triangles_skipped) +
             " degenerate triangle(s)");
    if (scene.meshes_without_normals)
        note(opt, scene.source + ": computed normals for " + std::to_string(scene.meshes_without_normals) +
                      " primitive(s) without normals");
    return scene;
}

// Reads --resume's checkpoint and refuses it when the scene or an image-shaping option differs.
Checkpoint open_resume(const Options& opt, const Json& fingerprint) {
    Checkpoint ck = read_checkpoint(opt.resume);
    if (!ck.header.contains("fingerprint")) throw Error(opt.resume + ": checkpoint has no fingerprint");
    std::string diff = checkpoint_differences(ck.header["fingerprint"], fingerprint);
    if (!diff.empty()) throw Error("--resume " + opt.resume + ": cannot continue this render: " + diff);
    return ck;
}

void save_checkpoint(const Options& opt, IntegratorBase& integ, const Json& fingerprint, const DeviceContext& dc) {
    Checkpoint ck;
    ck.header["version"] = kVersion;
    ck.header["fingerprint"] = fingerprint;
    ck.header["device"] = dc.info.name + " / " + dc.info.driver_version;
    integ.save(ck);
    write_checkpoint(opt.checkpoint, ck);
}

} // namespace

int render_session(const Options& given) {
    Options opt = given; // the integrator and its default pass count are settled with the scene
    Clock total;
    install_interrupt_handlers();
    // Several processes (mpirun): every rank renders the same passes on its share of the work;
    // rank 0 alone speaks, serves, writes and locks the outputs.
    Cluster& cl = cluster();
    const bool writer = cl.rank() == 0;
    set_interrupt_context(cl.size(), cl.rank());
    if (!writer) {
        opt.quiet = true;
        opt.serve.clear();
        opt.display_server.clear();
    }
    if (!opt.kernel_dir.empty()) set_kernel_dir(opt.kernel_dir);
    std::vector<DeviceInfo> devices = list_devices();
    const std::vector<DeviceInfo> chosen = choose_devices(opt, devices);
    const DeviceInfo& info = chosen.front();
    if (writer) check_outputs(opt);
    // Two renders writing the same files would mix their outputs: the second is refused.
    std::vector<std::string> outputs;
    if (writer) {
        outputs.push_back(opt.output);
        if (opt.write_png) outputs.push_back(png_path_for(opt.output));
        for (const std::string* p : {&opt.stats_json, &opt.checkpoint, &opt.error_output})
            if (!p->empty()) outputs.push_back(*p);
    }
    const OutputLock lock(outputs);
    // The live view listens from here on, so that a bad address fails before any work.
    std::unique_ptr<LiveView> live;
    if (!opt.serve.empty()) {
        const ServeAddress address = parse_serve_address(opt.serve);
        live = std::make_unique<LiveView>(address, opt.tone);
        std::fprintf(stderr, "clppm: live view at %s\n", live->url().c_str());
        if (!is_loopback(address.host))
            warn("--serve " + opt.serve + ": anyone who can reach this address can watch and stop the render");
    }
    std::unique_ptr<TevClient> tev;
    if (!opt.display_server.empty()) {
        const std::string name = opt.output.substr(opt.output.find_last_of('/') + 1);
        tev = std::make_unique<TevClient>(opt.display_server, name);
    }
    double last_tev_s = -1e9;

    Scene scene = load_scene(opt);
    std::string env_note;
    apply_environment(scene, opt.env, &env_note);
    if (!env_note.empty()) note(opt, env_note);
    const uint64_t scene_hash = scene_fingerprint(scene);
    std::string integrator_note; // said once the render is set up, after anything that can fail
    if (opt.integrator_auto) {
        const IntegratorChoice choice = default_integrator(scene);
        opt.integrator = choice.integrator;
        integrator_note = std::string("integrator ") + to_string(opt.integrator) + ": " + choice.reason;
    }
    // Integrators that add one sample per pixel and pass (no photons) default to the path tracer's passes.
    const bool pixel_samples =
        opt.integrator == Integrator::PT || opt.integrator == Integrator::VCM || opt.integrator == Integrator::BPT;
    if (opt.passes_default && pixel_samples) opt.passes = kPtDefaultPasses;
    RenderSettings settings = settings_from(opt);
    // Refuse a render the device cannot hold before allocating anything.
    const ImageResolution res = image_resolution(scene, settings);
    check_memory_fits(estimate_memory(scene, settings, res.width, res.height, info, wants_error_estimate(opt)), info);
    DeviceContext dc(info);
    DeviceScene ds = upload_scene(dc, scene, settings);
    for (const std::string& n : ds.notes) note(opt, n);
    for (const std::string& w : ds.warnings) warn(scene.source + ": " + w);
    // A gather radius beyond the scene gathers every photon everywhere, and an infinite one would
    // never end: refused, naming the scene's size.
    if (settings.radius > 2.0 * double(ds.info.radius)) {
        char msg[200];
        std::snprintf(msg, sizeof msg, "--radius %g: larger than the scene's bounding diameter %g (%s)",
                      settings.radius, 2.0 * double(ds.info.radius), scene.source.c_str());
        throw Error(msg);
    }

    const std::string program_file = integrator_program_file(settings);
    const SceneFeatures features = scene_features(scene, ds);
    const std::string build_options = integrator_build_options(
        settings, dc.info, opt.generic_kernels ? std::string() : feature_build_options(features));
    const std::string kernel_source = assemble_kernel_source(program_file);
    if (!opt.dump_kernel_source.empty())
        write_file_atomic(opt.dump_kernel_source, "// build options: " + build_options + "\n" + kernel_source);
    const Json fingerprint = image_fingerprint(opt, settings, ds, scene_hash, kernel_source + build_options);
    Checkpoint resume_from;
    if (!opt.resume.empty()) resume_from = open_resume(opt, fingerprint);

    ProgramBuildStats build;
    cl::Program program = build_program(dc, program_file, build_options, &build);
    note(opt, "device [" + std::to_string(dc.info.index) + "] " + dc.info.name + ", " +
                  std::to_string(ds.camera.width) + "x" + std::to_string(ds.camera.height) + ", " +
                  std::to_string(ds.num_triangles) + " triangles, " + std::to_string(ds.lights.size()) +
                  " lights, kernels " +
                  (opt.generic_kernels ? std::string("generic") : "for " + describe_features(features)) + " " +
                  (build.from_cache ? "cached" : "built") + " in " + std::to_string(build.seconds).substr(0, 5) + " s" +
                  (build.driver_cache ? " (the driver's cache)" : ""));

    if (!integrator_note.empty()) note(opt, integrator_note);
    if (cl.distributed())
        note(opt, std::to_string(cl.size()) + " processes (MPI): each pass's " +
                      (pixel_samples ? "pixels" : "photons") +
                      " are shared in proportion to each one's measured speed, their sums combined exactly" +
                      (settings.integrator == Integrator::VCM || settings.integrator == Integrator::BPT
                           ? " (every process traces all light sub-paths)"
                           : ""));
    // Light the path tracer cannot find: a point, spot or directional light seen through glass or
    // a mirror (a caustic) is a path of two delta events it never samples.
    if (settings.integrator == Integrator::PT && has_smooth_glass_or_mirror(scene) &&
        (features.point_lights || features.spot_lights || features.directional_lights))
        warn("the path tracer cannot find caustics of point, spot or directional lights through glass or mirrors: "
             "that light is missing from its image and from its error estimate (--integrator sppm finds it)");
    SecondaryDevices secondaries{std::vector<DeviceInfo>(chosen.begin() + 1, chosen.end()), program_file,
                                 build_options};
    if (!secondaries.devices.empty() && settings.integrator == Integrator::PT) {
        warn("the path tracer runs on the first device only");
        secondaries.devices.clear();
    }
    for (const DeviceInfo& d : secondaries.devices) {
        integrator_build_options(settings, d); // the same requirements (fp64) as the primary
        note(opt, std::string("sharing ") + (pixel_samples ? "pixels" : "photons") + " with device [" +
                      std::to_string(d.index) + "] " + d.name);
    }
    std::unique_ptr<IntegratorBase> integ = make_integrator(dc, ds, settings, program, secondaries);
    ErrorTracking errors;
    if (wants_error_estimate(opt)) {
        const char* asked = opt.target_error > 0 ? "--target-error" : "--error-output";
        if (!secondaries.devices.empty())
            throw Error(std::string(asked) + ": error estimation runs on one device; give a single --device");
        if (!integ->estimates_error())
            throw Error(std::string(asked) + ": the " + integ->name() + " integrator does not estimate its error");
        errors.integ = integ.get();
        errors.integ->enable_error_estimation();
    }
    Clock render_clock;
    integ->prepare();
    if (!opt.resume.empty()) {
        if (resume_from.header.value("device", std::string()) != dc.info.name + " / " + dc.info.driver_version)
            warn("resuming on another device than the checkpoint's (" +
                 resume_from.header.value("device", std::string("unknown")) + "): the image will not be bit-identical");
        integ->restore(resume_from);
        note(opt, "resumed " + opt.resume + " at pass " + std::to_string(integ->stats().passes));
        if (opt.passes > 0 && integ->stats().passes >= opt.passes)
            warn("--passes " + std::to_string(opt.passes) + ": the checkpoint already holds " +
                 std::to_string(integ->stats().passes) +
                 " passes (--passes counts from the start of the original render); nothing to render");
    }

    // --passes counts from the start of the original render (a total), --time this session only.
    Progress progress(opt.quiet, opt.passes, opt.time_limit);
    if (!opt.resume.empty()) progress.set_resumed(integ->stats().passes);
    double last_checkpoint = 0;
    int signal = 0;
    bool stopped_by_viewer = false;
    auto more = [&] {
        const uint64_t p = integ->stats().passes;
        if (opt.passes > 0 && p >= opt.passes) return false;
        if (opt.time_limit > 0 && render_clock.seconds() >= opt.time_limit) return false;
        if (errors.reached(opt)) return false;
        if (live && live->stop_requested()) return !(stopped_by_viewer = true);
        return (signal = interrupt_signal()) == 0;
    };
    // The live view's copy of the state: the film (a readback, which changes nothing), the error
    // map and the progress, as the progress line has them.
    auto publish = [&] {
        const IntegratorStats& st = integ->stats();
        const ProgressInfo p = progress.snapshot(st.passes, st.photons_emitted, st.mean_radius, render_clock.seconds());
        const nlohmann::json j = {{"pass", p.pass},
                                  {"pass_limit", p.pass_limit},
                                  {"time_limit", p.time_limit},
                                  {"photons", p.photons},
                                  {"radius", p.radius},
                                  {"elapsed_s", p.elapsed_s},
                                  {"passes_per_second", progress_rate(p)},
                                  {"eta_s", progress_eta(p)},
                                  {"error", errors.integ ? ErrorTracking::measure(opt, errors.last) : -1.0},
                                  {"target_error", opt.target_error},
                                  {"integrator", integ->name()}};
        const std::vector<float> none;
        live->publish(current_image(opt, *integ, 0), errors.integ ? errors.last.relative : none,
                      opt.target_error > 0 ? 2 * opt.target_error : 0.2, j);
    };
    // With several processes, rank 0's decision is everyone's (its clock, its viewer, its error
    // estimate), so that all ranks run the same passes; a rank's own Ctrl-C stops it at once.
    auto go_on = [&] {
        const bool go = more();
        if (!cl.distributed()) return go;
        try {
            const bool all = cl.from_rank0(go);
            if (!all && !writer) signal = 0; // rank 0 ended it (its signal, if any, is its own)
            return all && (signal = interrupt_signal()) == 0;
        } catch (const PassCancelled&) {
            signal = interrupt_signal();
            return false;
        }
    };
    while (go_on()) {
        try {
            integ->run_pass();
        } catch (const PassCancelled&) {
            signal = interrupt_signal(); // the statistics are those of the last complete pass
            break;
        }
        const IntegratorStats& st = integ->stats();
        errors.update(opt, progress, st.passes, render_clock.seconds());
        progress.update(st.passes, st.photons_emitted, st.mean_radius, render_clock.seconds());
        if (writer && opt.progressive_output > 0 && st.passes % opt.progressive_output == 0)
            save_images(opt, current_image(opt, *integ, 0), errors);
        if (tev && tev->connected() && render_clock.seconds() - last_tev_s >= 1.0 / LiveView::kPublishHz) {
            tev->send(current_image(opt, *integ, 0));
            last_tev_s = render_clock.seconds();
        }
        if (live) {
            if (live->due()) publish();
            if (live->take_save_request()) {
                save_images(opt, current_image(opt, *integ, 0), errors);
                note(opt,
                     "saved " + opt.output + " at pass " + std::to_string(st.passes) + " (asked by the live view)");
            }
        }
        if (writer && !opt.checkpoint.empty() &&
            ((opt.checkpoint_every > 0 && st.passes % opt.checkpoint_every == 0) ||
             render_clock.seconds() - last_checkpoint >= opt.checkpoint_interval)) {
            save_checkpoint(opt, *integ, fingerprint, dc);
            last_checkpoint = render_clock.seconds();
        }
    }
    const double render_s = render_clock.seconds();
    const IntegratorStats& st = integ->stats();
    progress.finish(st.passes, st.photons_emitted, st.mean_radius, render_s);
    if (stopped_by_viewer) note(opt, "stopped after pass " + std::to_string(st.passes) + " from the live view");
    if (tev && st.passes > 0) tev->send(current_image(opt, *integ, 0)); // the final image
    if (live && st.passes > 0) {
        publish(); // the final image, for whoever still watches while the outputs are written
        live->set_state(signal ? "interrupted" : "finished");
    }
    if (signal && st.passes == 0) {
        // Stopped before a single pass (during the kernel build, say): an image of zero passes
        // must not replace whatever the outputs hold.
        warn("interrupted before the first pass: nothing written, " + opt.output + " left as it was");
        return interrupted_exit_status(signal);
    }

    // Each rank's speed and time in communication, for the stats (a collective: only when every
    // rank got here, i.e. none was interrupted).
    Json mpi_stats;
    if (cl.distributed()) {
        mpi_stats = {{"ranks", cl.size()}};
        if (!signal) {
            try {
                const std::vector<double> work = cl.all_values(render_s > 0 ? double(st.local_work) / render_s : 0.0);
                const std::vector<double> comm = cl.all_values(cl.communication_seconds());
                mpi_stats[pixel_samples ? "samples_per_second" : "photons_per_second"] = work;
                mpi_stats["communication_seconds"] = comm;
            } catch (const PassCancelled&) {
                signal = interrupt_signal();
            }
        }
        mpi_stats["bytes_per_pass"] = st.passes ? double(cl.communication_bytes()) / double(st.passes) : 0.0;
        mpi_stats["last_pass_share"] = st.rank_photons;
        if (!writer) return signal ? interrupted_exit_status(signal) : 0;
    }

    Image img = current_image(opt, *integ, signal);
    save_images(opt, img, errors);
    if (!opt.error_output.empty() && !errors.last.relative.empty()) save_error_images(opt, errors.last);
    if (errors.integ) {
        char line[300];
        std::snprintf(line, sizeof line,
                      "estimated error %.4g (90th percentile of the relative error), bound %.4g (confidence %g)%s",
                      errors.last.expected_error, errors.last.image_error, opt.confidence,
                      errors.reached(opt) ? ": reached the target" : "");
        note(opt, line);
        // PPM's fixed samples leave an error no pass removes: say so when it is what stopped the
        // estimate short of the target.
        const ErrorImage& e = errors.last;
        if (opt.target_error > 0 && !errors.reached(opt) && e.sample_floor > opt.target_error &&
            e.sample_floor >= 0.8 * e.expected_error) {
            std::snprintf(line, sizeof line,
                          "--target-error %g: out of PPM's reach here; its %d fixed samples per pixel alone leave an "
                          "estimated error of %.3g (--spp more, or --integrator sppm, which samples anew every pass)",
                          opt.target_error, opt.spp, e.sample_floor);
            warn(line);
        }
    }
    if (!opt.checkpoint.empty()) save_checkpoint(opt, *integ, fingerprint, dc);
    // Radiance is finite and never negative: a pixel that is not is a defect, said loudly (the
    // image is kept, so nothing rendered is lost) and the exit status says the render failed.
    const size_t nonfinite = count_nonfinite(img), negative = count_negative(img);
    if (nonfinite || negative)
        std::fprintf(stderr, "clppm: error: %zu pixel(s) are NaN or Inf and %zu negative in %s (a renderer defect)\n",
                     nonfinite, negative, opt.output.c_str());
    if (!opt.stats_json.empty()) {
        Json j = make_stats(opt, dc, ds, scene, *integ, build, render_s, total.seconds(), img, signal);
        if (!mpi_stats.is_null()) j["mpi"] = mpi_stats;
        if (live)
            j["live_view"] = {{"url", live->url()}, {"requests", live->requests()}, {"stopped_it", stopped_by_viewer}};
        if (errors.integ)
            j["error"] = {{"estimated", errors.last.expected_error},
                          {"bound", errors.last.image_error},
                          {"target", opt.target_error},
                          {"stops_on", opt.error_bound ? "bound" : "estimate"},
                          {"reached", errors.reached(opt)},
                          {"confidence", opt.confidence},
                          {"percentile", kErrorPercentile},
                          {"passes", errors.last.passes}};
        write_stats_json(opt.stats_json, j);
    }
    note(opt, "wrote " + opt.output + (opt.write_png ? " and " + png_path_for(opt.output) : std::string()) +
                  (opt.error_output.empty() ? std::string() : " and " + opt.error_output) +
                  (opt.checkpoint.empty() ? std::string() : " and " + opt.checkpoint));
    if (signal) {
        warn("interrupted after pass " + std::to_string(st.passes) +
             (opt.checkpoint.empty() ? std::string() : "; continue with --resume " + opt.checkpoint));
        return interrupted_exit_status(signal);
    }
    return nonfinite || negative ? 1 : 0;
}

} // namespace clppm
