#include "integrators/integrator_table.h"

#include "integrators/photon_map.h"
#include "integrators/ppm_integrator.h"
#include "integrators/pt_integrator.h"
#include "integrators/sppm_integrator.h"
#include "integrators/vcm_integrator.h"
#include "shared_types.h"
#include "util/error.h"
#include "util/text.h"
#include "vcm_mis.h"

namespace clppm {

namespace {

template <class T>
std::unique_ptr<IntegratorBase> make(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                                     const cl::Program& program, const SecondaryDevices& secondaries) {
    return std::make_unique<T>(dc, scene, settings, program, secondaries);
}

IntegratorMemory sppm_memory(const RenderSettings& settings, size_t pixels, bool errors) {
    return SppmIntegrator::memory_needed(pixels, errors, settings.volume_gather == VolumeGather::Beams);
}
IntegratorMemory pt_memory(const RenderSettings&, size_t pixels, bool errors) {
    return PtIntegrator::memory_needed(pixels, errors);
}
IntegratorMemory vcm_memory(const RenderSettings&, size_t pixels, bool errors) {
    return VcmIntegrator::memory_needed(pixels, errors);
}
size_t photon_memory(const RenderSettings& settings, size_t pixels, const DeviceInfo& device) {
    return PhotonMap::memory_needed(settings, device, pixels);
}
size_t no_transport_memory(const RenderSettings&, size_t, const DeviceInfo&) { return 0; }
size_t light_vertex_memory(const RenderSettings&, size_t pixels, const DeviceInfo& device) {
    return VcmIntegrator::light_vertex_bytes(pixels, device);
}

// Passes of one sample per pixel are about 8 times cheaper than a photon pass at 512x512: 512 of
// them take about as long as 64 photon passes. A VCM or BPT pass also traces a light sub-path per
// pixel and connects it: 0.70 s at 512x512 on the Cornell box against SPPM's 0.21 s (measured,
// two-core PoCL CPU), so 16 of them take about as long as SPPM's 64.
constexpr uint64_t kPhotonPasses = 64, kPixelPasses = 512, kConnectionPasses = 16;

const std::vector<IntegratorRow> kTable = {
    {"ppm", nullptr, "progressive photon mapping (fixed hit points, Hachisuka et al. 2008)", "ppm_program.cl",
     PPM_EYE_SLOTS, WorkUnit::Photons, kPhotonPasses, true, true, true, "", PpmIntegrator::memory_needed, photon_memory,
     make<PpmIntegrator>, nullptr, true, kProgressiveRadii, true, false},
    {"sppm", nullptr, "stochastic PPM (a new eye sample per pixel every pass)", "sppm_program.cl", SPPM_EYE_SLOTS,
     WorkUnit::Photons, kPhotonPasses, true, true, true, "", sppm_memory, photon_memory, make<SppmIntegrator>, nullptr,
     true, kProgressiveRadii, true, true},
    {"pppm", nullptr, "probabilistic PPM (independent passes, Knaus and Zwicker 2011)", "sppm_program.cl",
     SPPM_EYE_SLOTS, WorkUnit::Photons, kPhotonPasses, true, true, true, "", sppm_memory, photon_memory,
     make<SppmIntegrator>, nullptr, false, kProbabilisticRadii, true, true},
    {"pt", nullptr, "path tracing", "path_trace.cl", PPM_EYE_SLOTS, WorkUnit::Pixels, kPixelPasses, false, true, true,
     "", pt_memory, no_transport_memory, make<PtIntegrator>, PtIntegrator::warnings, false, 0, true, false},
    {"vcm", nullptr, "vertex connection and merging (bidirectional path tracing and photon merging under MIS)",
     "vcm_program.cl", PPM_EYE_SLOTS, WorkUnit::Pixels, kConnectionPasses, true, false, true,
     " (every process traces all light sub-paths)", vcm_memory, light_vertex_memory, make<VcmIntegrator>, nullptr,
     false, VCM_MODE_VCM, false, false},
    {"bpt", "bdpt", "bidirectional path tracing", "vcm_program.cl", PPM_EYE_SLOTS, WorkUnit::Pixels, kConnectionPasses,
     true, false, true, " (every process traces all light sub-paths)", vcm_memory, light_vertex_memory,
     make<VcmIntegrator>, nullptr, false, VCM_MODE_BPT, false, false},
};

} // namespace

const std::vector<IntegratorRow>& integrator_table() { return kTable; }

const IntegratorRow& integrator_row(const std::string& name) {
    const std::string n = lower(name);
    for (const IntegratorRow& row : kTable)
        if (n == row.name || (row.alias && n == row.alias)) return row;
    throw Error("unknown integrator " + name + " (one of " + integrator_names() + ")");
}

std::string integrator_names() {
    std::vector<std::string> names;
    for (const IntegratorRow& row : kTable) names.push_back(row.name);
    return either(names);
}

namespace {

// "a, b or c": the integrators whose row has `column` set.
std::string integrators_with(bool IntegratorRow::*column) {
    std::vector<std::string> names;
    for (const IntegratorRow& row : kTable)
        if (row.*column) names.push_back(row.name);
    return either(names);
}

} // namespace

std::string visual_importance_integrators() { return integrators_with(&IntegratorRow::visual_importance); }

std::string media_integrators() { return integrators_with(&IntegratorRow::media); }

void require_media_support(const IntegratorRow& row, bool scene_has_medium, VolumeGather gather) {
    if (!scene_has_medium) return;
    if (!row.media)
        throw Error(std::string("--integrator ") + row.name +
                    ": the scene has a participating medium (extras.clppm_medium, --medium-density or "
                    "KHR_materials_volume_scatter), which only " +
                    media_integrators() + " can render so far; pick one, or --no-medium for the world's");
    if (gather == VolumeGather::Beams && !row.volume_beams)
        throw Error(std::string("--volume-gather beams: --integrator ") + row.name +
                    " gathers the medium at points; only " + integrators_with(&IntegratorRow::volume_beams) +
                    " gather along beams");
}

std::unique_ptr<IntegratorBase> make_integrator(const DeviceContext& dc, const DeviceScene& scene,
                                                const RenderSettings& settings, const cl::Program& program,
                                                const SecondaryDevices& secondaries) {
    const IntegratorRow& row = integrator_row(settings.integrator);
    require_media_support(row, scene.media, settings.volume_gather);
    RenderSettings canonical = settings; // the integrators compare names as the table spells them
    canonical.integrator = row.name;
    return row.make(dc, scene, canonical, program, secondaries);
}

std::string integrator_build_options(const RenderSettings& settings, const DeviceInfo& device,
                                     const std::string& features) {
    if (!device.fp64)
        throw Error("device " + device.name +
                    " lacks double precision (cl_khr_fp64), which clppm's hit point statistics need; pick another "
                    "with --device");
    // PPM splits an eye sample at glass and metal into several hit points; SPPM and PPPM keep
    // one visible point per pixel and pass.
    std::string options = "-DEYE_SLOTS=" + std::to_string(integrator_row(settings.integrator).eye_slots);
    if (settings.filter == PixelFilter::Tent) options += " -DPIXEL_FILTER_TENT";
    // The path tracer's numbers, compiled in alone: PoCL if-converts a run-time choice into both.
    if (settings.sampler == Sampler::Independent) options += " -DPATH_SAMPLER_INDEPENDENT";
    if (settings.visual_importance) options += " -DPHOTON_VISUAL_IMPORTANCE";
    if (!features.empty()) options += " " + features;
    return options;
}

} // namespace clppm
