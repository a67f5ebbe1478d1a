// Launching kernels and creating, filling and moving buffers: the few calls every host stage makes.
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

// Reads a whole device buffer of n elements into a vector, and writes one back; write_bytes writes
// `bytes` bytes of `data` to b at `offset` (blocking).
template <class T>
std::vector<T> read_buffer(const cl::CommandQueue& q, const cl::Buffer& b, size_t n) {
    std::vector<T> v(n);
    if (n) q.enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(T), v.data());
    return v;
}
void write_bytes(const cl::CommandQueue& q, const cl::Buffer& b, size_t offset, size_t bytes, const void* data);
template <class T>
void write_buffer(const cl::CommandQueue& q, const cl::Buffer& b, const std::vector<T>& v) {
    if (!v.empty()) q.enqueueWriteBuffer(b, CL_TRUE, 0, v.size() * sizeof(T), v.data());
}

// CLPPM_OCLGRIND=1 (scripts/check_oclgrind.sh) fits buffer handling to how oclgrind 21.10's
// --uninitialized check keeps its shadow memory, which says which bytes of a buffer hold written
// values. It never undoes anything, so three things that are right on every OpenCL would make it
// report reads of values that were written. None changes an image (tests/cli_test.cpp):
//   - a released buffer's shadow stays with its slot, and a later buffer in the slot keeps the old
//     size, so that writes past it are lost (VCM's light vertices, in a slot the footprint buffer
//     had held, read as uninitialised past its 256 bytes): buffers are kept until the process ends;
//   - a host write replaces the buffer's shadow by one the size of the write, which a write of part
//     of a buffer leaves misplaced: such writes write the whole buffer (read, patch, write back);
//   - what clEnqueueFillBuffer writes is not marked as written: fills are host writes.
bool oclgrind_mode();

// A buffer of `bytes` bytes (and `host`'s contents with CL_MEM_COPY_HOST_PTR): every buffer the
// host stages create comes from here.
cl::Buffer make_buffer(const cl::Context& context, cl_mem_flags flags, size_t bytes, void* host = nullptr);

// Fills `bytes` bytes of b from `offset` with copies of `pattern` (clEnqueueFillBuffer; host writes
// under CLPPM_OCLGRIND).
template <class T>
void fill_buffer(const cl::CommandQueue& q, const cl::Buffer& b, const T& pattern, size_t offset, size_t bytes) {
    if (bytes == 0) return;
    if (!oclgrind_mode()) {
        q.enqueueFillBuffer(b, pattern, offset, bytes);
        return;
    }
    const std::vector<T> copies(bytes / sizeof(T), pattern);
    write_bytes(q, b, offset, bytes, copies.data());
}

} // namespace clppm
