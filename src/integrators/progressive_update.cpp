#include "integrators/progressive_update.h"

#include <algorithm>
#include <vector>

#include "device/kernel_launch.h"
#include "shared_types.h"

namespace clppm {

size_t radius_partials_bytes(uint32_t n) {
    return (std::max<uint32_t>(1, n) + PPM_UPDATE_WG - 1) / PPM_UPDATE_WG * sizeof(cl_float2);
}

std::pair<double, double> enqueue_ppm_update(const DeviceContext& dc, cl::Kernel& kernel, const cl::Buffer& passflux,
                                             const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                                             double alpha, bool volume_stats, const cl::Buffer& radius_partials,
                                             IntegratorStats& istats) {
    if (n == 0) return {0.0, 0.0};
    set_args(kernel, 0, passflux, hitpoints, stats, cl_uint(n), cl_double(alpha), cl_uint(volume_stats ? 1 : 0),
             radius_partials);
    const size_t groups = (n + PPM_UPDATE_WG - 1) / PPM_UPDATE_WG;
    cl::Event ev;
    dc.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(groups * PPM_UPDATE_WG),
                                  cl::NDRange(PPM_UPDATE_WG), nullptr, &ev);
    std::vector<cl_float2> partials = read_buffer<cl_float2>(dc.queue, radius_partials, groups);
    add_event_time(istats, "update", ev);
    double sum = 0, mx = 0;
    for (const cl_float2& p : partials) sum += p.s[0], mx = std::max(mx, double(p.s[1]));
    return {sum / n, mx};
}

} // namespace clppm
