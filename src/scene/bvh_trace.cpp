#include "scene/bvh_trace.h"
#include "device/kernel_launch.h"

#include <algorithm>

#include "device/kernel_program.h"

namespace clppm {

namespace {

template <class T>
cl::Buffer upload(const DeviceContext& dc, const std::vector<T>& v) {
    // Zero-sized buffers are invalid in OpenCL: an empty array still gets one element.
    const size_t bytes = std::max<size_t>(1, v.size()) * sizeof(T);
    cl::Buffer b = make_buffer(dc.context, CL_MEM_READ_ONLY, bytes);
    if (!v.empty()) dc.queue.enqueueWriteBuffer(b, CL_TRUE, 0, v.size() * sizeof(T), v.data());
    return b;
}

} // namespace

DeviceBvh::DeviceBvh(const DeviceContext& dc, const std::vector<dev::BvhNode>& built,
                     const std::vector<Vec3>& positions) {
    std::vector<dev::BvhNode> n = built;
    const std::vector<dev::BvhTriBlock> b = bvh_leaf_blocks(n, positions);
    nodes = upload(dc, n);
    blocks = upload(dc, b);
}

RayTracer::RayTracer(const DeviceContext& dc, const std::string& build_options)
    : dc_(dc), program_(build_program(dc, "trace_rays.cl", build_options)), kernel_(program_, "trace_rays") {}

cl::Event RayTracer::enqueue(const DeviceBvh& bvh, const cl::Buffer& rays, const cl::Buffer& hits, uint32_t n,
                             size_t local_size) {
    kernel_.setArg(0, bvh.nodes);
    kernel_.setArg(1, bvh.blocks);
    kernel_.setArg(2, rays);
    kernel_.setArg(3, hits);
    kernel_.setArg(4, n);
    cl::Event ev;
    if (n == 0) return ev;
    const size_t global = local_size ? (n + local_size - 1) / local_size * local_size : n;
    dc_.queue.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(global),
                                   local_size ? cl::NDRange(local_size) : cl::NullRange, nullptr, &ev);
    return ev;
}

std::vector<TraceHit> RayTracer::trace(const DeviceBvh& bvh, const std::vector<TraceRay>& rays, size_t local_size) {
    std::vector<TraceHit> hits(rays.size());
    if (rays.empty()) return hits;
    cl::Buffer ray_buf = upload(dc_, rays);
    cl::Buffer hit_buf = make_buffer(dc_.context, CL_MEM_WRITE_ONLY, hits.size() * sizeof(TraceHit));
    enqueue(bvh, ray_buf, hit_buf, uint32_t(rays.size()), local_size);
    dc_.queue.enqueueReadBuffer(hit_buf, CL_TRUE, 0, hits.size() * sizeof(TraceHit), hits.data());
    return hits;
}

} // namespace clppm
