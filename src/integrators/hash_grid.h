// The uniform hashed grid of kernels/hash_grid.cl over one batch of points (photons, or vertex
// connection and merging's light vertices): counting sort by cell into a second buffer, and the
// bucket starts a gather walks (SmallVCM HashGrid). The program decides the element type
// (GRID_ELEM); element_bytes is its size.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/integrator_stats.h"
#include "shared_types.h"

namespace clppm {

class HashGrid {
public:
    // kernels: the prefix of the program's count and scatter kernels ("": grid_count and
    // grid_scatter, every element; "beam_": kernels/beam.cl's, the photons stored in media only).
    HashGrid(const DeviceContext& dc, const cl::Program& program, IntegratorStats& stats,
             const std::string& kernels = "");

    // Sorts elements [0, n) of `elements` into `sorted` by cubic cells of side `cell` from `origin`
    // (timed as "grid_build").
    void build(const cl::Buffer& elements, const cl::Buffer& sorted, uint32_t n, const float origin[3], double cell);

    // What a gather takes: the GridInfo and the n_buckets + 1 bucket starts.
    const cl::Buffer& info() const { return info_; }
    const cl::Buffer& starts() const { return starts_; }

    size_t device_bytes() const { return (2 * size_t(table_size_) + 1) * sizeof(cl_uint); }
    // Device memory of the table for n elements.
    static size_t bytes_for(uint64_t n);

private:
    const DeviceContext& dc_;
    IntegratorStats& stats_;
    cl::Kernel k_count_, k_scan_, k_scatter_;
    cl::Buffer info_, counts_, starts_;
    dev::GridInfo host_{}; // read by a non-blocking write after build() returns
    uint32_t table_size_ = 0;
};

// Buckets for n elements: a power of two, at least 1024.
uint32_t hash_grid_table_size(uint64_t n);

} // namespace clppm
