/* trace_rays.cl: a batch of independent ray queries, for the BVH tests and the traversal benchmark.
 *
 * rays: 8 floats per ray, ox oy oz tmax dx dy dz any_hit (0 or 1, as float).
 * hits: one float4 per ray, (t, u, v, as_float(prim)); a miss is t = -1, prim = 0xffffffff.
 * With -DBVH_STATS, u and v carry the nodes visited and triangles tested instead. */
#include "portability.h"
#include "bvh_traverse.cl"

__kernel SCALAR_WORK_ITEMS void trace_rays(__global const BvhNode* nodes, __global const BvhTriBlock* blocks,
                                           __global const float* rays, __global float4* hits, uint n) {
    const uint i = get_global_id(0);
    if (i >= n) return;
    const float4 o = vload4(2 * i, rays), d = vload4(2 * i + 1, rays);
    Hit h;
    const bool found = bvh_intersect(nodes, blocks, o.xyz, d.xyz, o.w, d.w != 0.0f, &h);
    float4 out = found ? (float4)(h.t, h.u, h.v, as_float(h.prim)) : (float4)(-1.0f, 0.0f, 0.0f, as_float(0xffffffffu));
#ifdef BVH_STATS
    /* Benchmark diagnostics: counters in place of the barycentrics. */
    out.y = (float)h.nodes_visited;
    out.z = (float)h.tris_tested;
#endif
    hits[i] = out;
}
