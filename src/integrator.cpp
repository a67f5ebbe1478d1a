#include "integrator.h"

#include <algorithm>
#include <cstdlib>

#include "error.h"
#include "ppm_integrator.h"
#include "pt_integrator.h"
#include "sppm_integrator.h"

namespace clppm {

std::unique_ptr<IntegratorBase> make_integrator(const DeviceContext& dc, const DeviceScene& scene,
                                                const RenderSettings& settings, const cl::Program& program,
                                                const SecondaryDevices& secondaries) {
    if (settings.integrator == Integrator::PT) return std::make_unique<PtIntegrator>(dc, scene, settings, program);
    if (settings.integrator == Integrator::SPPM || settings.integrator == Integrator::PPPM)
        return std::make_unique<SppmIntegrator>(dc, scene, settings, program, secondaries);
    return std::make_unique<PpmIntegrator>(dc, scene, settings, program, secondaries);
}

std::string integrator_program_file(const RenderSettings& settings) {
    switch (settings.integrator) {
    case Integrator::PT: return "path_trace.cl";
    case Integrator::SPPM:
    case Integrator::PPPM: return "sppm_program.cl";
    default: return "ppm_program.cl";
    }
}

std::string integrator_build_options(const RenderSettings& settings, const DeviceInfo& device,
                                     const std::string& features) {
    if (!device.fp64)
        throw Error("device " + device.name +
                    " lacks double precision (cl_khr_fp64), which clppm's hit point statistics need; pick another "
                    "with --device");
    std::string options;
    // SPPM and PPPM keep one visible point per pixel and pass; PPM splits into up to four.
    if (settings.integrator == Integrator::SPPM || settings.integrator == Integrator::PPPM) options += "-DEYE_SLOTS=1";
    else options += "-DEYE_SLOTS=4";
    if (settings.filter == PixelFilter::Tent) options += " -DPIXEL_FILTER_TENT";
    if (!features.empty()) options += " " + features;
    return options;
}

void IntegratorBase::save(Checkpoint& ck) {
    Json& h = ck.header;
    h["passes"] = stats_.passes;
    h["photons_emitted"] = stats_.photons_emitted;
    h["photons_stored"] = stats_.photons_stored;
    h["hitpoints"] = stats_.hitpoints;
    h["initial_radius"] = stats_.initial_radius;
    h["mean_radius"] = stats_.mean_radius;
    Json phases = Json::object();
    for (const auto& [k, v] : stats_.phase_seconds) phases[k] = v;
    h["phase_seconds"] = phases;
}

void IntegratorBase::restore(const Checkpoint& ck) {
    const Json& h = ck.header;
    try {
        stats_.passes = h.at("passes").get<uint64_t>();
        stats_.photons_emitted = h.at("photons_emitted").get<uint64_t>();
        stats_.photons_stored = h.at("photons_stored").get<uint64_t>();
        stats_.initial_radius = h.at("initial_radius").get<double>();
        stats_.mean_radius = h.at("mean_radius").get<double>();
        if (h.at("hitpoints").get<uint64_t>() != stats_.hitpoints)
            throw Error(ck.path + ": checkpoint has " + h.at("hitpoints").dump() + " hit points, this render " +
                        std::to_string(stats_.hitpoints) + " (a different device or clppm version?)");
        stats_.phase_seconds.clear();
        for (auto it = h.at("phase_seconds").begin(); it != h.at("phase_seconds").end(); ++it)
            stats_.phase_seconds[it.key()] = it.value().get<double>();
    } catch (const nlohmann::json::exception& e) {
        throw Error(ck.path + ": checkpoint header lacks the pass counters (" + std::string(e.what()) + ")");
    }
}

void enqueue_1d(const cl::CommandQueue& queue, const cl::Kernel& kernel, size_t n, cl::Event* event) {
    static const size_t local = [] {
        const char* e = std::getenv("CLPPM_LOCAL_SIZE");
        return e && *e ? size_t(std::strtoul(e, nullptr, 10)) : size_t(0);
    }();
    n = std::max<size_t>(n, 1);
    if (local > 0) {
        size_t global = (n + local - 1) / local * local;
        queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), cl::NDRange(local), nullptr, event);
    } else {
        queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n), cl::NullRange, nullptr, event);
    }
}

void add_event_time(IntegratorStats& stats, const std::string& phase, const cl::Event& ev) {
    stats.pending_events.emplace_back(phase, ev);
}

void collect_event_times(IntegratorStats& stats) {
    for (auto& [phase, ev] : stats.pending_events) {
        try {
            ev.wait();
            cl_ulong t0 = ev.getProfilingInfo<CL_PROFILING_COMMAND_START>();
            cl_ulong t1 = ev.getProfilingInfo<CL_PROFILING_COMMAND_END>();
            stats.phase_seconds[phase] += double(t1 - t0) * 1e-9;
        } catch (const cl::Error&) {
            // Profiling unavailable for this event: the phase time stays as it was.
        }
    }
    stats.pending_events.clear();
}

} // namespace clppm
