// Device memory a render will need, worked out before anything is allocated, so that a render
// too large for the device is refused with the numbers and the options that shrink it instead of
// failing somewhere inside the driver.
#pragma once
#include <cstddef>
#include <string>

#include "device/device.h"
#include "integrators/render_settings.h"
#include "scene/scene.h"

namespace clppm {

struct MemoryEstimate {
    size_t scene = 0;      // BVH, triangles, shading data, materials, textures, lights
    size_t integrator = 0; // hit points or per-pixel statistics, film
    size_t photons = 0;    // photon and grid buffers (batched to fit, see PhotonMap)
    size_t largest_buffer = 0;
    size_t total() const { return scene + integrator + photons; }
};

// The scene's buffers, the integrator's own (each integrator reports them: integrator_memory) and
// the photons'. error_estimation: --target-error or --error-output adds its buffers.
MemoryEstimate estimate_memory(const Scene& scene, const RenderSettings& settings, unsigned width, unsigned height,
                               const DeviceInfo& device, bool error_estimation = false);

// Throws Error when the estimate does not fit the device, naming what is needed, what the device
// has and which options reduce it.
void check_memory_fits(const MemoryEstimate& m, const DeviceInfo& device);

} // namespace clppm
