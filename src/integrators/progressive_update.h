// The progressive update of PPM and SPPM (Hachisuka et al. 2008, Eqs. 7-10) over n hit points:
// kernels/ppm_update.cl, and the per-group radius partials that size the next pass's grid; and
// the global radius of PPPM and VCM.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/integrator_stats.h"

namespace clppm {

// Runs ppm_update over n hit points and returns (mean, max) of R after it. volume_stats: volume
// hit points keep statistics of their own (PPM's fixed ones), else they are left alone.
std::pair<double, double> enqueue_ppm_update(const DeviceContext& dc, cl::Kernel& kernel, const cl::Buffer& passflux,
                                             const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                                             double alpha, bool volume_stats, const cl::Buffer& radius_partials,
                                             IntegratorStats& istats);

// Bytes of the per-group radius partials enqueue_ppm_update needs for n hit points.
size_t radius_partials_bytes(uint32_t n);

// One global radius for every pixel, as probabilistic PPM and VCM's merging shrink it (Knaus and
// Zwicker 2011, Eq. 20): r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1), i the 1-based pass.
inline double next_pppm_radius2(double r2, uint64_t i, double alpha) {
    return r2 * (double(i) + alpha) / double(i + 1);
}

} // namespace clppm
