#include "integrator.h"

#include "error.h"
#include "ppm_integrator.h"
#include "pt_integrator.h"

namespace clppm {

std::unique_ptr<IntegratorBase> make_integrator(const DeviceContext& dc, const DeviceScene& scene,
                                                const RenderSettings& settings, const cl::Program& program) {
    if (settings.integrator == Integrator::PT) return std::make_unique<PtIntegrator>(dc, scene, settings, program);
    return std::make_unique<PpmIntegrator>(dc, scene, settings, program);
}

std::string integrator_program_file(const RenderSettings& settings) {
    return settings.integrator == Integrator::PT ? "path_trace.cl" : "ppm_program.cl";
}

std::string integrator_build_options(const RenderSettings& settings, const DeviceInfo& device) {
    if (!device.fp64)
        throw Error("device " + device.name +
                    " lacks double precision (cl_khr_fp64), which clppm's hit point statistics need; pick another "
                    "with --device");
    return "";
}

void add_event_time(IntegratorStats& stats, const std::string& phase, const cl::Event& ev) {
    try {
        cl_ulong t0 = ev.getProfilingInfo<CL_PROFILING_COMMAND_START>();
        cl_ulong t1 = ev.getProfilingInfo<CL_PROFILING_COMMAND_END>();
        stats.phase_seconds[phase] += double(t1 - t0) * 1e-9;
    } catch (const cl::Error&) {
        // Profiling unavailable for this event: the phase time stays as it was.
    }
}

} // namespace clppm
