// What the benchmark programs share: an in-process render they can step pass by pass and sample
// at any moment, a wall clock, and small output helpers. Benchmarks measure; they never fail on
// a time.
#pragma once
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "device/device.h"
#include "device/kernel_program.h"
#include "integrators/integrator_table.h"
#include "scene/device_scene.h"
#include "scene/environment.h"
#include "scene/gltf/gltf_load.h"
#include "scene/scene_features.h"
#include "util/error.h"
#include "util/steady_seconds.h"

namespace clppm::bench {

inline double now_s() { return steady_seconds(); }

// A benchmark scene by name, or a glTF file by path; lit as the command line lights it (a scene
// without lights by the default white environment).
inline Scene load_named_scene(const std::string& name) {
    Scene scene = name.empty() || name == "cornell_box" ? load_default_scene()
                  : name.find('/') != std::string::npos
                      ? load_gltf(name)
                      : load_gltf(std::string(CLPPM_SOURCE_DIR) + "/scenes/" + name + ".gltf");
    apply_environment(scene, EnvironmentSettings{}, nullptr);
    return scene;
}

// A render in this process on one device: build, prepare, then passes on demand.
struct Render {
    DeviceContext dc;
    Scene scene;
    DeviceScene ds;
    cl::Program program;
    ProgramBuildStats build;
    std::unique_ptr<IntegratorBase> integ;
    double prepare_seconds = 0;

    // error_estimation: enabled before prepare(), as PPM needs.
    Render(const DeviceInfo& device, const std::string& scene_name, const RenderSettings& s, bool generic = false,
           bool error_estimation = false)
        : dc(device), scene(load_named_scene(scene_name)) {
        ds = upload_scene(dc, scene, s);
        std::string features = generic ? std::string() : feature_build_options(scene_features(scene, ds));
        program = build_program(dc, integrator_row(s.integrator).program_file,
                                integrator_build_options(s, device, features), &build);
        integ = make_integrator(dc, ds, s, program);
        if (error_estimation) integ->enable_error_estimation();
        double t0 = now_s();
        integ->prepare();
        dc.queue.finish();
        prepare_seconds = now_s() - t0;
    }
};

inline const DeviceInfo& bench_device(const std::string& spec) {
    static std::vector<DeviceInfo> devices = list_devices();
    if (!spec.empty()) return select_device(devices, spec);
    for (const DeviceInfo& d : devices)
        if (d.type & CL_DEVICE_TYPE_GPU) return d;
    return select_device(devices, "0");
}

// The options every timed benchmark takes; a benchmark's own Args derive from it.
struct BenchOptions {
    bool quick = false;    // a smoke run: small and short
    std::string device;    // as clppm --device takes it; empty: a GPU if there is one
    std::string out = "."; // where the results go
    double seconds = 6;    // per measurement
};

inline void add_bench_options(CLI::App& app, BenchOptions& o, const std::string& quick, const std::string& out,
                              const std::string& seconds) {
    app.add_flag("--quick", o.quick, quick);
    app.add_option("--device", o.device, "An OpenCL device, as clppm --device takes it");
    app.add_option("--out", o.out, out);
    app.add_option("--seconds", o.seconds, seconds);
}

inline std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

} // namespace clppm::bench
