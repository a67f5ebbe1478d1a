#include "device/kernel_launch.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace clppm {

bool fill_by_write() {
    static const bool on = [] {
        const char* e = std::getenv("CLPPM_FILL_BY_WRITE");
        return e && *e && std::string(e) != "0";
    }();
    return on;
}

void enqueue_1d(const cl::CommandQueue& queue, const cl::Kernel& kernel, size_t n, cl::Event* event) {
    enqueue_1d_range(queue, kernel, 0, n, event);
}

void enqueue_1d_range(const cl::CommandQueue& queue, const cl::Kernel& kernel, size_t first, size_t n,
                      cl::Event* event) {
    static const size_t forced = [] {
        const char* e = std::getenv("CLPPM_LOCAL_SIZE");
        return e && *e ? size_t(std::strtoul(e, nullptr, 10)) : size_t(0);
    }();
    n = std::max<size_t>(n, 1);
    const cl::NDRange offset = first ? cl::NDRange(first) : cl::NullRange;
    size_t local = forced;
    if (local == 0) {
        // The kernel's limit on this device, as a power of two no larger than kWorkGroupSize.
        const cl::Device device = queue.getInfo<CL_QUEUE_DEVICE>();
        const size_t limit = kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device);
        local = 1;
        while (local * 2 <= std::min(limit, kWorkGroupSize)) local *= 2;
    }
    const size_t global = (n + local - 1) / local * local;
    queue.enqueueNDRangeKernel(kernel, offset, cl::NDRange(global), cl::NDRange(local), nullptr, event);
}

} // namespace clppm
