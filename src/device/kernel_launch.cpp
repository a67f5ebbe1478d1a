#include "device/kernel_launch.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

namespace clppm {

bool oclgrind_mode() {
    static const bool on = [] {
        const char* e = std::getenv("CLPPM_OCLGRIND");
        return e && *e && std::string(e) != "0";
    }();
    return on;
}

cl::Buffer make_buffer(const cl::Context& context, cl_mem_flags flags, size_t bytes, void* host) {
    cl::Buffer b(context, flags, bytes, host);
    if (oclgrind_mode()) {
        // Never destroyed: released at exit, its slot is never handed to another buffer.
        static std::mutex lock;
        static auto* kept = new std::vector<cl::Buffer>;
        const std::lock_guard<std::mutex> hold(lock);
        kept->push_back(b);
    }
    return b;
}

void write_bytes(const cl::CommandQueue& q, const cl::Buffer& b, size_t offset, size_t bytes, const void* data) {
    if (bytes == 0) return;
    const size_t size = oclgrind_mode() ? b.getInfo<CL_MEM_SIZE>() : 0;
    if (size == 0 || (offset == 0 && bytes == size)) { // outside oclgrind, or the whole buffer
        q.enqueueWriteBuffer(b, CL_TRUE, offset, bytes, data);
        return;
    }
    std::vector<unsigned char> whole(size);
    q.enqueueReadBuffer(b, CL_TRUE, 0, size, whole.data());
    std::memcpy(whole.data() + offset, data, bytes);
    q.enqueueWriteBuffer(b, CL_TRUE, 0, size, whole.data());
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
