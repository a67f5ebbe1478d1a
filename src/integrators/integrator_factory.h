// Making the integrator a render asks for, its kernel program and the device memory it needs:
// the one place that knows every concrete integrator.
#pragma once
#include <memory>
#include <string>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/integrator.h"
#include "integrators/render_settings.h"
#include "scene/device_scene.h"

namespace clppm {

std::unique_ptr<IntegratorBase> make_integrator(const DeviceContext& dc, const DeviceScene& scene,
                                                const RenderSettings& settings, const cl::Program& program,
                                                const SecondaryDevices& secondaries = {});

// The kernel program an integrator needs.
std::string integrator_program_file(const RenderSettings& settings);
// The build options of an integrator's program; `features` (feature_build_options) specialises it
// for a scene, "" builds the generic program. Throws Error for a device the integrators cannot
// run on (no double precision).
std::string integrator_build_options(const RenderSettings& settings, const DeviceInfo& device,
                                     const std::string& features = "");

// The integrator's own device buffers for a width x height image (integrators/memory_estimate.h
// adds the scene and the photons).
IntegratorMemory integrator_memory(const RenderSettings& settings, unsigned width, unsigned height,
                                   bool error_estimation);

} // namespace clppm
