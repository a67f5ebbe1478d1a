// Explicit direct lighting at hit points (kernels/direct_light.cl): one light sample per hit
// point and pass, added to stats[i].direct; the film divides by the passes.
#pragma once
#include <cstdint>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/integrator_stats.h"
#include "scene/device_scene.h"

namespace clppm {

void enqueue_direct_light(const DeviceContext& dc, const DeviceScene& scene, cl::Kernel& kernel, uint64_t seed,
                          uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                          IntegratorStats& istats);

} // namespace clppm
