// The one table of integrators (pbrt-v4's Integrator::Create, one row each): what the render
// loop, the memory estimate, the options and the default need to know of an integrator. A new
// integrator is its own files and one row here; nothing else names a concrete integrator.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/integrator.h"
#include "integrators/render_settings.h"
#include "scene/device_scene.h"
#include "scene/scene.h"
#include "scene/scene_features.h"

namespace clppm {

// What a pass's work is shared out in between devices and processes: the pass's photons, or its
// pixels (one sample each).
enum class WorkUnit { Photons, Pixels };

struct IntegratorRow {
    const char* name;         // --integrator's value, and the name in stats, EXR headers and checkpoints
    const char* alias;        // another accepted spelling ("bdpt", pbrt's), or nullptr
    const char* summary;      // for --help
    const char* program_file; // its kernel program (kernels/*_program.cl)
    int eye_slots;            // EYE_SLOTS of its program: hit points an eye sample may leave
    WorkUnit unit;
    uint64_t default_passes; // without --passes or --time
    bool several_devices;    // shares passes between devices (else the first device alone renders)
    bool tent_filter;        // supports --filter tent
    bool estimates_error;    // progressive error estimation (--target-error, --error-output)
    const char* mpi_note;    // how processes share its passes, beyond the unit ("" when nothing more)
    // Its own device buffers for `pixels` pixels (hit points or per-pixel statistics, film, error
    // estimation), and those of its photons or light vertices (0: none).
    IntegratorMemory (*memory)(const RenderSettings& settings, size_t pixels, bool error_estimation);
    size_t (*transport_memory)(const RenderSettings& settings, size_t pixels, const DeviceInfo& device);
    std::unique_ptr<IntegratorBase> (*make)(const DeviceContext& dc, const DeviceScene& scene,
                                            const RenderSettings& settings, const cl::Program& program,
                                            const SecondaryDevices& secondaries);
    // What it cannot render of this scene, said as a warning before the first pass (may be null).
    std::vector<std::string> (*warnings)(const Scene& scene, const SceneFeatures& features);
    bool visual_importance; // takes --visual-importance: photon paths that Markov chains guide
    uint32_t mode;          // which variant of its class: kProbabilisticRadii (PPPM), VCM_MODE_* (VCM, BPT), or 0
    bool media;             // renders the world's participating medium (kernels/medium.cl)
    bool volume_beams;      // gathers media along the camera rays with --volume-gather beams (kernels/beam.cl)
};

// IntegratorRow::mode of the photon mappers: SPPM's shrinking radii, PPPM's independent passes.
constexpr uint32_t kProgressiveRadii = 0, kProbabilisticRadii = 1;

// "ppm or sppm": the integrators that take --visual-importance.
std::string visual_importance_integrators();

// Every integrator, in --help's order.
const std::vector<IntegratorRow>& integrator_table();

// The row of `name` (or its alias, any case). Throws Error listing the names for anything else
// ("auto" included: it is resolved by default_integrator first).
const IntegratorRow& integrator_row(const std::string& name);

// "ppm, sppm, pppm, pt, vcm or bpt".
std::string integrator_names();

// "ppm, sppm, pppm or pt": the integrators that render participating media.
std::string media_integrators();

// Throws Error, naming --integrator, where the scene has a medium that the integrator cannot render, or asks for beams
// (--volume-gather beams) that it does not gather.
void require_media_support(const IntegratorRow& row, bool scene_has_medium, VolumeGather gather);

// The integrator of settings.integrator for a scene on the device. Throws Error for a scene with a
// medium that it does not render.
std::unique_ptr<IntegratorBase> make_integrator(const DeviceContext& dc, const DeviceScene& scene,
                                                const RenderSettings& settings, const cl::Program& program,
                                                const SecondaryDevices& secondaries = {});

// The build options of settings.integrator's program; `features` (feature_build_options)
// specialises it for a scene, "" builds the generic program. Throws Error for a device the
// integrators cannot run on (no double precision).
std::string integrator_build_options(const RenderSettings& settings, const DeviceInfo& device,
                                     const std::string& features = "");

} // namespace clppm
