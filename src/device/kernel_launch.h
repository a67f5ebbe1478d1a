// Launching kernels and moving whole buffers: the few calls every host stage makes.
#pragma once
#include <cstddef>
#include <vector>

#include "device/cl.h"

namespace clppm {

// Sets kernel arguments first, first + 1, ... to args in order; returns the index after the last.
template <class... Args>
int set_args(cl::Kernel& kernel, int first, const Args&... args) {
    (kernel.setArg(first++, args), ...);
    return first;
}

// Work-group size of every 1-D launch (or the kernel's limit on the device, if lower): one size for
// every launch, so that PoCL compiles each kernel's work-group function once. Left to the driver,
// the size followed each global size (light vertex and photon counts change every pass), and PoCL
// compiled a new variant for many passes: a VCM render of the Cornell box at 128x128 took 22.7 s
// for 200 passes, 8.1 s with a fixed size (bench/RESULTS.md).
constexpr size_t kWorkGroupSize = 64;

// Launches a 1-D kernel over n work items, rounded up to whole work-groups (the kernel ignores ids
// >= n). CLPPM_LOCAL_SIZE overrides the work-group size; the tests use it to show that images do
// not depend on it.
void enqueue_1d(const cl::CommandQueue& queue, const cl::Kernel& kernel, size_t n, cl::Event* event = nullptr);
// Work items first .. first + n - 1 (get_global_id counts from `first`); the kernel bounds-checks
// against the range's end as it does against n above.
void enqueue_1d_range(const cl::CommandQueue& queue, const cl::Kernel& kernel, size_t first, size_t n,
                      cl::Event* event = nullptr);

// Reads a whole device buffer of n elements into a vector, and writes one back.
template <class T>
std::vector<T> read_buffer(const cl::CommandQueue& q, const cl::Buffer& b, size_t n) {
    std::vector<T> v(n);
    if (n) q.enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(T), v.data());
    return v;
}
template <class T>
void write_buffer(const cl::CommandQueue& q, const cl::Buffer& b, const std::vector<T>& v) {
    if (!v.empty()) q.enqueueWriteBuffer(b, CL_TRUE, 0, v.size() * sizeof(T), v.data());
}

// Fills `bytes` bytes of b from `offset` with copies of `pattern` (clEnqueueFillBuffer). With
// CLPPM_FILL_BY_WRITE=1 it writes the copies from the host instead: oclgrind 21.10 does not mark
// what clEnqueueFillBuffer wrote as initialised, and its --uninitialized check
// (scripts/check_oclgrind.sh) then flags every read of a filled buffer. Same bytes either way.
bool fill_by_write();
template <class T>
void fill_buffer(const cl::CommandQueue& q, const cl::Buffer& b, const T& pattern, size_t offset, size_t bytes) {
    if (bytes == 0) return;
    if (!fill_by_write()) {
        q.enqueueFillBuffer(b, pattern, offset, bytes);
        return;
    }
    const std::vector<T> copies(bytes / sizeof(T), pattern);
    q.enqueueWriteBuffer(b, CL_TRUE, offset, bytes, copies.data());
}

} // namespace clppm
