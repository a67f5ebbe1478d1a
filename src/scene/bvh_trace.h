// The host side of kernels/trace_rays.cl: a built BVH in device buffers and batched ray queries
// against it (what the BVH tests and the traversal benchmark run; the renderer's own kernels
// include bvh_traverse.cl directly).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "device/device.h"
#include "scene/bvh_build.h"

namespace clppm {

// Node and triangle-block buffers of one BVH as build_bvh left it (leaves pointing at triangles in
// BvhBuildResult::tri_order; `positions` already in that order).
struct DeviceBvh {
    cl::Buffer nodes, blocks;
    DeviceBvh(const DeviceContext& dc, const std::vector<dev::BvhNode>& nodes, const std::vector<Vec3>& positions);
};

// A ray for trace_rays: 8 floats, ox oy oz tmax dx dy dz any_hit.
struct TraceRay {
    float org[3];
    float tmax;
    float dir[3];
    float any_hit; // 0 or 1
};
static_assert(sizeof(TraceRay) == 32, "trace_rays reads 8 floats per ray");

// One result: t (-1 on a miss), barycentrics u, v of v1 and v2, triangle id (~0u on a miss).
struct TraceHit {
    float t, u, v;
    uint32_t prim;
    bool hit() const { return t >= 0; }
};
static_assert(sizeof(TraceHit) == 16, "trace_rays writes one float4 per ray");

class RayTracer {
public:
    explicit RayTracer(const DeviceContext& dc, const std::string& build_options = "");
    // Blocking convenience: uploads the rays, traces, reads back.
    std::vector<TraceHit> trace(const DeviceBvh& bvh, const std::vector<TraceRay>& rays, size_t local_size = 0);
    // Enqueues one launch over n rays already on the device; local_size 0 lets the driver choose.
    cl::Event enqueue(const DeviceBvh& bvh, const cl::Buffer& rays, const cl::Buffer& hits, uint32_t n,
                      size_t local_size = 0);

private:
    const DeviceContext& dc_;
    cl::Program program_;
    cl::Kernel kernel_;
};

} // namespace clppm
