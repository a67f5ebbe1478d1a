// The progressive update of PPM and SPPM (Hachisuka et al. 2008, Eqs. 7-10) over n hit points:
// kernels/ppm_update.cl, and the per-group radius partials that size the next pass's grid.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/integrator_stats.h"

namespace clppm {

// Runs ppm_update over n hit points and returns (mean, max) of R after it.
std::pair<double, double> enqueue_ppm_update(const DeviceContext& dc, cl::Kernel& kernel, const cl::Buffer& passflux,
                                             const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                                             double alpha, const cl::Buffer& radius_partials, IntegratorStats& istats);

// Bytes of the per-group radius partials enqueue_ppm_update needs for n hit points.
size_t radius_partials_bytes(uint32_t n);

} // namespace clppm
