/* bvh_traverse.cl: closest-hit and any-hit ray queries against the wide BVH built by
 * src/scene/bvh_build.cpp. One traversal routine serves both (any_hit is a flag, not a second copy).
 *
 * Triangles: blocks of BVH_TRI_BLOCK with SoA vertices (shared_types.h, src/scene/bvh_build.cpp
 * bvh_leaf_blocks), tested together.
 * Node test: BVH_WIDTH slab tests at once on the SoA child bounds, nearest child first, the others on
 * a private stack with their entry distance so that closest-hit skips what lies beyond its hit.
 * Triangle test: the watertight test of Woop, Benthin and Wald 2013 (JCGT 2(1)). */
#ifndef CLPPM_BVH_TRAVERSE_CL
#define CLPPM_BVH_TRAVERSE_CL

#include "shared_types.h"

typedef struct {
    float t;
    float u, v; /* barycentrics of v1 and v2 */
    uint prim;  /* triangle id in BVH leaf order */
#ifdef BVH_STATS
    uint nodes_visited, tris_tested; /* -DBVH_STATS: traversal counters for the benchmark */
#endif
} Hit;

/* min/max without NaN handling (none can arise here): a compare and a select are one maxps. */
#define BVH_VMIN(a, b) select((b), (a), isless((a), (b)))
#define BVH_VMAX(a, b) select((b), (a), isgreater((a), (b)))

#define BVH_STACK_SIZE ((BVH_WIDTH - 1) * BVH_MAX_DEPTH + 1)

/* One vector lane per child slot. */
#if BVH_WIDTH == 8
typedef float8 bvh_floatw;
#define BVH_VSTORE vstore8
inline int bvh_lane_mask(int8 in) {
    return (in.s0 & 1) | (in.s1 & 2) | (in.s2 & 4) | (in.s3 & 8) | (in.s4 & 16) | (in.s5 & 32) | (in.s6 & 64) |
           (in.s7 & 128);
}
#else
typedef float4 bvh_floatw;
#define BVH_VSTORE vstore4
inline int bvh_lane_mask(int4 in) { return (in.x & 1) | (in.y & 2) | (in.z & 4) | (in.w & 8); }
#endif

/* One vector lane per triangle of a block. */
#if BVH_TRI_BLOCK == 8
typedef float8 bvh_floatb;
typedef int8 bvh_intb;
#define BVH_VSTOREB vstore8
inline int bvh_block_mask(int8 in) {
    return (in.s0 & 1) | (in.s1 & 2) | (in.s2 & 4) | (in.s3 & 8) | (in.s4 & 16) | (in.s5 & 32) | (in.s6 & 64) |
           (in.s7 & 128);
}
#else
typedef float4 bvh_floatb;
typedef int4 bvh_intb;
#define BVH_VSTOREB vstore4
inline int bvh_block_mask(int4 in) { return (in.x & 1) | (in.y & 2) | (in.z & 4) | (in.w & 8); }
#endif

/* Ize 2013, "Robust BVH ray traversal", Sec. 3: widening the far slab distance by 1 + 2 gamma(3)
 * keeps rounding in the slab test from culling a box the ray grazes. */
#define BVH_FAR_SCALE 1.00000036f

/* The ray in the sheared, permuted frame of Woop et al. (Sec. 3): the direction becomes +z; a
 * vertex p maps to (p[kx] - o[kx] - sx (p[kz] - o[kz]), p[ky] - o[ky] - sy (p[kz] - o[kz]),
 * sz (p[kz] - o[kz])). */
typedef struct {
    int kx, ky, kz;
    float ox, oy, oz; /* org[kx], org[ky], org[kz] */
    float sx, sy, sz;
} RayShear;

inline float vec3_component(float3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

inline RayShear ray_shear(float3 org, float3 dir, float3 idir) {
    const float3 a = fabs(dir);
    /* kz: axis of largest |dir|; kx, ky follow it cyclically, swapped when dir[kz] < 0 to keep
     * the winding (the test is two-sided anyway, but the sign of det stays meaningful). */
    RayShear s;
    s.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    s.kx = s.kz == 2 ? 0 : s.kz + 1;
    s.ky = s.kx == 2 ? 0 : s.kx + 1;
    const float dz = vec3_component(dir, s.kz);
    if (dz < 0.0f) {
        const int tmp = s.kx;
        s.kx = s.ky;
        s.ky = tmp;
    }
    /* Components by selects, not by indexing a private array (which went through memory). */
    s.ox = vec3_component(org, s.kx);
    s.oy = vec3_component(org, s.ky);
    s.oz = vec3_component(org, s.kz);
    s.sz = vec3_component(idir, s.kz); /* 1 / dz, unless the ray is degenerate (all |dir| < 1e-20) */
    s.sx = vec3_component(dir, s.kx) * s.sz;
    s.sy = vec3_component(dir, s.ky) * s.sz;
    return s;
}

/* Woop et al. 2013, Fig. 1, on the BVH_TRI_BLOCK triangles of one block at once (without the
 * double-precision fallback: an edge function that rounds to exactly 0 counts as inside for both
 * triangles sharing that edge). The block stores each vertex as the mesh has it, and every lane
 * maps a vertex through the same operations, so triangles sharing an edge see bitwise identical
 * endpoints there and no ray passes between them. Returns the lanes (bit i: lane i) hit at
 * 0 < t < tmax, with t, u (weight of v1), v (weight of v2) per lane. */
/* Inlined by force: as a call (PoCL's inliner declines) every leaf would spill the ray state. */
inline __attribute__((always_inline)) int intersect_block(__global const BvhTriBlock* block, const RayShear* s,
                                                          float tmax, bvh_floatb* t_out, bvh_floatb* u_out,
                                                          bvh_floatb* v_out) {
    /* No fused multiply-add here: edge(P, Q) must be exactly -edge(Q, P) for shared edges. */
#pragma OPENCL FP_CONTRACT OFF
    __global const bvh_floatb* row = (__global const bvh_floatb*)block;
    const bvh_floatb az = row[s->kz] - s->oz, bz = row[3 + s->kz] - s->oz, cz = row[6 + s->kz] - s->oz;
    const bvh_floatb ax = (row[s->kx] - s->ox) - s->sx * az, ay = (row[s->ky] - s->oy) - s->sy * az;
    const bvh_floatb bx = (row[3 + s->kx] - s->ox) - s->sx * bz, by = (row[3 + s->ky] - s->oy) - s->sy * bz;
    const bvh_floatb cx = (row[6 + s->kx] - s->ox) - s->sx * cz, cy = (row[6 + s->ky] - s->oy) - s->sy * cz;
    const bvh_floatb U = cx * by - cy * bx;
    const bvh_floatb V = ax * cy - ay * cx;
    const bvh_floatb W = bx * ay - by * ax;
    const bvh_floatb zero = (bvh_floatb)(0.0f);
    const bvh_intb outside = ((U < zero) | (V < zero) | (W < zero)) & ((U > zero) | (V > zero) | (W > zero));
    const bvh_floatb det = U + V + W;
    const bvh_floatb T = U * (s->sz * az) + V * (s->sz * bz) + W * (s->sz * cz);
    /* 0 < t = T / det < tmax, tested before paying for the division. */
    const bvh_floatb abs_det = fabs(det), abs_T = select(T, -T, det < zero);
    const bvh_intb ok = ~outside & (det != zero) & (abs_T > zero) & (abs_T < tmax * abs_det);
    const int mask = bvh_block_mask(ok);
    if (mask == 0) return 0;
    const bvh_floatb inv_det = 1.0f / det;
    *t_out = T * inv_det;
    *u_out = V * inv_det;
    *v_out = W * inv_det;
    return mask;
}

/* The hook for intersections that may not count (alpha.cl): a file included before this one
 * may define BVH_FILTER(prim, u, v), true when the intersection counts, with the extra parameters
 * it needs (BVH_FILTER_PARAMS, a list that starts with a comma) and their names (BVH_FILTER_ARGS);
 * org and dir are in scope. Without it every intersection counts and nothing is added. */
#ifndef BVH_FILTER
#define BVH_FILTER_PARAMS
#define BVH_FILTER_ARGS
#define BVH_FILTER(prim, u, v) true
#endif

/* Closest hit in (0, tmax) when !any_hit (fills *hit); any hit in (0, tmax) when any_hit (fills
 * *hit with the one found). Returns whether there was a hit. */
bool bvh_intersect(__global const BvhNode* nodes, __global const BvhTriBlock* blocks, float3 org, float3 dir,
                   float tmax, bool any_hit, Hit* hit BVH_FILTER_PARAMS) {
    /* Slab test setup. A zero direction component would give 1/0 = inf and then 0 * inf = NaN on
     * a box face through the origin; a tiny stand-in keeps every product finite and ordered. */
    const float3 safe_dir = select(dir, copysign((float3)(1e-20f), dir), isless(fabs(dir), (float3)(1e-20f)));
    const float3 idir = 1.0f / safe_dir;
    const bvh_floatw ox = (bvh_floatw)(org.x), oy = (bvh_floatw)(org.y), oz = (bvh_floatw)(org.z);
    const bvh_floatw ix = (bvh_floatw)(idir.x), iy = (bvh_floatw)(idir.y), iz = (bvh_floatw)(idir.z);
    /* Vector rows of a node: 0..2 bmin x,y,z; 3..5 bmax x,y,z; 6 child; 7 count. The near plane of
     * each axis is bmin for a positive direction and bmax otherwise (by idir: -0 counts as negative). */
    const int near_x = idir.x >= 0.0f ? 0 : 3, near_y = idir.y >= 0.0f ? 1 : 4, near_z = idir.z >= 0.0f ? 2 : 5;
    const int far_x = 3 - near_x, far_y = 5 - near_y, far_z = 7 - near_z;

    const RayShear shear = ray_shear(org, dir, idir);

    int stack_node[BVH_STACK_SIZE];
    uint stack_count[BVH_STACK_SIZE];
    float stack_dist[BVH_STACK_SIZE];
    int sp = 0;

    float t_best = tmax;
    bool found = false;
    int cur = 0; /* >= 0: inner node; < 0: leaf with first triangle ~cur */
    uint cur_count = 0;
#ifdef BVH_STATS
    hit->nodes_visited = hit->tris_tested = 0;
#endif
    for (;;) {
        if (cur >= 0) {
#ifdef BVH_STATS
            ++hit->nodes_visited;
#endif
            __global const bvh_floatw* row = (__global const bvh_floatw*)(nodes + cur);
            const bvh_floatw tnx = (row[near_x] - ox) * ix, tfx = (row[far_x] - ox) * ix;
            const bvh_floatw tny = (row[near_y] - oy) * iy, tfy = (row[far_y] - oy) * iy;
            const bvh_floatw tnz = (row[near_z] - oz) * iz, tfz = (row[far_z] - oz) * iz;
            const bvh_floatw tnear = BVH_VMAX(BVH_VMAX(tnx, tny), BVH_VMAX(tnz, (bvh_floatw)(0.0f)));
            const bvh_floatw tfar = BVH_VMIN(BVH_VMIN(tfx, tfy), BVH_VMIN(tfz, (bvh_floatw)(t_best))) * BVH_FAR_SCALE;
            const int mask = bvh_lane_mask(islessequal(tnear, tfar));
            if (mask != 0) {
                /* Children straight from the node, without a private copy (no slower in traversal_bench). */
                __global const int* c = (__global const int*)(row + 6);
                __global const uint* n = (__global const uint*)(row + 7);
                float d[BVH_WIDTH];
                BVH_VSTORE(tnear, 0, d);
                if ((mask & (mask - 1)) == 0) { /* one child: descend without touching the stack */
                    const int i = 31 - clz(mask);
                    cur = c[i];
                    cur_count = n[i];
                    continue;
                }
                /* Several: push them all, sorted so the nearest ends on top, then pop it. Any-hit
                 * keeps slot order instead: nearest-first from a surface point wades through the
                 * surface it leaves, and unsorted any-hit ran 2x faster on diffuse bounces. */
                const int base = sp;
                for (int m = mask; m != 0; m &= m - 1) {
                    const int i = 31 - clz(m & -m);
                    int j = sp++;
                    while (!any_hit && j > base && stack_dist[j - 1] < d[i]) {
                        stack_node[j] = stack_node[j - 1];
                        stack_count[j] = stack_count[j - 1];
                        stack_dist[j] = stack_dist[j - 1];
                        --j;
                    }
                    stack_node[j] = c[i];
                    stack_count[j] = n[i];
                    stack_dist[j] = d[i];
                }
                --sp;
                cur = stack_node[sp];
                cur_count = stack_count[sp];
                continue;
            }
        } else {
            const uint first = (uint)(~cur);
            for (uint b = first; b < first + (cur_count + BVH_TRI_BLOCK - 1) / BVH_TRI_BLOCK; ++b) {
#ifdef BVH_STATS
                hit->tris_tested += min(cur_count - (b - first) * BVH_TRI_BLOCK, (uint)BVH_TRI_BLOCK);
#endif
                bvh_floatb t4, u4, v4;
                int lanes = intersect_block(blocks + b, &shear, t_best, &t4, &u4, &v4);
                if (lanes == 0) continue;
                float t[BVH_TRI_BLOCK], u[BVH_TRI_BLOCK], v[BVH_TRI_BLOCK];
                BVH_VSTOREB(t4, 0, t);
                BVH_VSTOREB(u4, 0, u);
                BVH_VSTOREB(v4, 0, v);
                /* Every lane that hits, nearer than the best so far and accepted by the filter. A
                 * repeated triangle (unused lanes) is the same hit again and changes nothing. */
                for (; lanes != 0; lanes &= lanes - 1) {
                    const int i = 31 - clz(lanes & -lanes);
                    if (!(t[i] > 0.0f && t[i] < t_best)) continue;
                    const uint p = blocks[b].prim[i];
                    if (!BVH_FILTER(p, u[i], v[i])) continue;
                    found = true;
                    t_best = t[i];
                    hit->t = t[i];
                    hit->u = u[i];
                    hit->v = v[i];
                    hit->prim = p;
                    if (any_hit) return true;
                }
            }
        }
        /* Pop the nearest pending entry that can still beat the best hit. */
        for (;;) {
            if (sp == 0) return found;
            --sp;
            if (stack_dist[sp] <= t_best) break;
        }
        cur = stack_node[sp];
        cur_count = stack_count[sp];
    }
}

#endif
