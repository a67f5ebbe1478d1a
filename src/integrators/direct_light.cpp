#include "integrators/direct_light.h"

#include "device/kernel_launch.h"

namespace clppm {

void enqueue_direct_light(const DeviceContext& dc, const DeviceScene& scene, cl::Kernel& kernel, uint64_t seed,
                          uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                          IntegratorStats& istats) {
    if (n == 0) return;
    set_args(kernel, scene.set_scene_args(kernel), cl_ulong(seed), cl_ulong(pass), hitpoints, stats, cl_uint(n));
    cl::Event ev;
    enqueue_1d(dc.queue, kernel, n, &ev);
    add_event_time(istats, "direct_light", ev);
}

} // namespace clppm
