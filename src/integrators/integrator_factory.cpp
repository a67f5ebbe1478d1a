#include "integrators/integrator_factory.h"

#include "integrators/ppm_integrator.h"
#include "integrators/pt_integrator.h"
#include "integrators/sppm_integrator.h"
#include "integrators/vcm_integrator.h"
#include "shared_types.h"
#include "util/error.h"

namespace clppm {

std::unique_ptr<IntegratorBase> make_integrator(const DeviceContext& dc, const DeviceScene& scene,
                                                const RenderSettings& settings, const cl::Program& program,
                                                const SecondaryDevices& secondaries) {
    switch (settings.integrator) {
    case Integrator::PPM: return std::make_unique<PpmIntegrator>(dc, scene, settings, program, secondaries);
    case Integrator::SPPM:
    case Integrator::PPPM: return std::make_unique<SppmIntegrator>(dc, scene, settings, program, secondaries);
    case Integrator::PT: return std::make_unique<PtIntegrator>(dc, scene, settings, program);
    case Integrator::VCM:
    case Integrator::BPT: return std::make_unique<VcmIntegrator>(dc, scene, settings, program, secondaries);
    }
    throw Error("unknown integrator");
}

std::string integrator_program_file(const RenderSettings& settings) {
    switch (settings.integrator) {
    case Integrator::PPM: return "ppm_program.cl";
    case Integrator::SPPM:
    case Integrator::PPPM: return "sppm_program.cl";
    case Integrator::PT: return "path_trace.cl";
    case Integrator::VCM:
    case Integrator::BPT: return "vcm_program.cl";
    }
    throw Error("unknown integrator");
}

std::string integrator_build_options(const RenderSettings& settings, const DeviceInfo& device,
                                     const std::string& features) {
    if (!device.fp64)
        throw Error("device " + device.name +
                    " lacks double precision (cl_khr_fp64), which clppm's hit point statistics need; pick another "
                    "with --device");
    std::string options;
    switch (settings.integrator) {
    // PPM splits an eye sample at glass and metal into several hit points; SPPM and PPPM keep
    // one visible point per pixel and pass. The path tracer has no eye pass, but shares the files.
    case Integrator::PPM:
    case Integrator::PT:
    case Integrator::VCM:
    case Integrator::BPT: options = "-DEYE_SLOTS=" + std::to_string(PPM_EYE_SLOTS); break;
    case Integrator::SPPM:
    case Integrator::PPPM: options = "-DEYE_SLOTS=" + std::to_string(SPPM_EYE_SLOTS); break;
    }
    switch (settings.filter) {
    case PixelFilter::Box: break;
    case PixelFilter::Tent: options += " -DPIXEL_FILTER_TENT"; break;
    }
    if (!features.empty()) options += " " + features;
    return options;
}

IntegratorMemory integrator_memory(const RenderSettings& settings, unsigned width, unsigned height,
                                   bool error_estimation) {
    const size_t pixels = size_t(width) * height;
    switch (settings.integrator) {
    case Integrator::PPM: return PpmIntegrator::memory_needed(settings, pixels, error_estimation);
    case Integrator::SPPM:
    case Integrator::PPPM: return SppmIntegrator::memory_needed(pixels, error_estimation);
    case Integrator::PT: return PtIntegrator::memory_needed(pixels, error_estimation);
    case Integrator::VCM:
    case Integrator::BPT: return VcmIntegrator::memory_needed(pixels);
    }
    throw Error("unknown integrator");
}

} // namespace clppm
