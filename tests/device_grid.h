// The hashed photon grid of kernels/hash_grid.cl built on the test device for the gather tests
// (gather_test.cpp, beam_gather_test.cpp): count, scan, scatter, as PhotonMap builds it.
#pragma once
#include <string>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "shared_types.h"

namespace clppm::test {

// What a gather kernel takes of a grid: its GridInfo, the photons sorted by bucket and each
// bucket's first.
struct DeviceGrid {
    cl::Buffer info, sorted, starts;
};

// A read-write buffer holding a copy of `bytes` at data.
inline cl::Buffer copy_buffer(const cl::Context& ctx, const void* data, size_t bytes) {
    return cl::Buffer(ctx, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(data));
}

// Sorts photons into the grid g (its table_size buckets) with program's `kernels`grid_count and
// `kernels`grid_scatter ("": every photon; "beam_": kernels/beam.cl's, the photons in media).
inline DeviceGrid build_device_grid(const DeviceContext& dc, const cl::Program& program, const dev::GridInfo& g,
                                    const std::vector<dev::Photon>& photons, const std::string& kernels = "") {
    const cl::Context& ctx = dc.context;
    DeviceGrid grid;
    grid.info = copy_buffer(ctx, &g, sizeof g);
    cl::Buffer in = copy_buffer(ctx, photons.data(), photons.size() * sizeof(dev::Photon));
    grid.sorted = cl::Buffer(ctx, CL_MEM_READ_WRITE, photons.size() * sizeof(dev::Photon));
    std::vector<cl_uint> zeros(g.table_size, 0);
    cl::Buffer counts = copy_buffer(ctx, zeros.data(), zeros.size() * sizeof(cl_uint));
    grid.starts = cl::Buffer(ctx, CL_MEM_READ_WRITE, (zeros.size() + 1) * sizeof(cl_uint));
    cl::Kernel count(program, (kernels + "grid_count").c_str()), scan(program, "grid_scan"),
        scatter(program, (kernels + "grid_scatter").c_str());
    count.setArg(0, grid.info), count.setArg(1, in), count.setArg(2, counts);
    scan.setArg(0, counts), scan.setArg(1, grid.starts), scan.setArg(2, cl_uint(g.table_size));
    scatter.setArg(0, grid.info), scatter.setArg(1, in), scatter.setArg(2, grid.starts), scatter.setArg(3, counts);
    scatter.setArg(4, grid.sorted);
    dc.queue.enqueueNDRangeKernel(count, cl::NullRange, cl::NDRange(photons.size()));
    dc.queue.enqueueNDRangeKernel(scan, cl::NullRange, cl::NDRange(GRID_SCAN_WG), cl::NDRange(GRID_SCAN_WG));
    dc.queue.enqueueNDRangeKernel(scatter, cl::NullRange, cl::NDRange(photons.size()));
    return grid;
}

} // namespace clppm::test
