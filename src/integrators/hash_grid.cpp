#include "integrators/hash_grid.h"

#include <algorithm>

#include "device/kernel_launch.h"

namespace clppm {

uint32_t hash_grid_table_size(uint64_t n) {
    const uint64_t want = std::clamp<uint64_t>(n, 1024, uint64_t(1) << 31);
    uint32_t p = 1;
    while (p < want) p <<= 1;
    return p;
}

size_t HashGrid::bytes_for(uint64_t n) { return (2 * size_t(hash_grid_table_size(n)) + 1) * sizeof(cl_uint); }

HashGrid::HashGrid(const DeviceContext& dc, const cl::Program& program, IntegratorStats& stats,
                   const std::string& kernels)
    : dc_(dc), stats_(stats) {
    k_count_ = cl::Kernel(program, (kernels + "grid_count").c_str());
    k_scan_ = cl::Kernel(program, "grid_scan");
    k_scatter_ = cl::Kernel(program, (kernels + "grid_scatter").c_str());
    info_ = make_buffer(dc.context, CL_MEM_READ_ONLY, sizeof(dev::GridInfo));
}

void HashGrid::build(const cl::Buffer& elements, const cl::Buffer& sorted, uint32_t n, const float origin[3],
                     double cell) {
    dev::GridInfo& g = host_;
    g = dev::GridInfo{};
    for (int k = 0; k < 3; ++k) g.origin[k] = origin[k];
    g.inv_cell = float(1.0 / cell);
    g.num_photons = n;
    g.table_size = hash_grid_table_size(n);
    if (g.table_size != table_size_) {
        table_size_ = g.table_size;
        counts_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, size_t(table_size_) * sizeof(cl_uint));
        starts_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, size_t(table_size_ + 1) * sizeof(cl_uint));
    }
    dc_.queue.enqueueWriteBuffer(info_, CL_FALSE, 0, sizeof g, &g);
    fill_buffer(dc_.queue, counts_, cl_uint(0), 0, size_t(table_size_) * sizeof(cl_uint));
    cl::Event e1, e2, e3;
    set_args(k_count_, 0, info_, elements, counts_);
    enqueue_1d(dc_.queue, k_count_, n, &e1);
    set_args(k_scan_, 0, counts_, starts_, cl_uint(table_size_));
    dc_.queue.enqueueNDRangeKernel(k_scan_, cl::NullRange, cl::NDRange(GRID_SCAN_WG), cl::NDRange(GRID_SCAN_WG),
                                   nullptr, &e2);
    set_args(k_scatter_, 0, info_, elements, starts_, counts_, sorted);
    enqueue_1d(dc_.queue, k_scatter_, n, &e3);
    add_event_time(stats_, "grid_build", e1);
    add_event_time(stats_, "grid_build", e2);
    add_event_time(stats_, "grid_build", e3);
}

} // namespace clppm
