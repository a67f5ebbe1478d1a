/* bvh_traverse.cl: closest-hit and any-hit ray queries against the wide BVH built by
 * src/scene/bvh_build.cpp. One traversal routine serves both (any_hit is a flag, not a second copy).
 *
 * Triangles: 3 float4 each, v0, e1 = v1 - v0, e2 = v2 - v0 (src/scene/bvh_build.cpp, bvh_triangle_data).
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
#define BVH_AS_INTW as_int8
#define BVH_AS_UINTW as_uint8
#define BVH_VSTORE vstore8
inline int bvh_lane_mask(int8 in) {
    return (in.s0 & 1) | (in.s1 & 2) | (in.s2 & 4) | (in.s3 & 8) | (in.s4 & 16) | (in.s5 & 32) | (in.s6 & 64) |
           (in.s7 & 128);
}
#else
typedef float4 bvh_floatw;
#define BVH_AS_INTW as_int4
#define BVH_AS_UINTW as_uint4
#define BVH_VSTORE vstore4
inline int bvh_lane_mask(int4 in) { return (in.x & 1) | (in.y & 2) | (in.z & 4) | (in.w & 8); }
#endif

/* Ize 2013, "Robust BVH ray traversal", Sec. 3: widening the far slab distance by 1 + 2 gamma(3)
 * keeps rounding in the slab test from culling a box the ray grazes. */
#define BVH_FAR_SCALE 1.00000036f

/* The ray in the sheared, permuted frame of Woop et al. (Sec. 3): the direction becomes +z and
 * a vertex p maps to M (p - org), M stored by columns (m0 takes p.x, ...). */
typedef struct {
    float4 m0, m1, m2;
} RayShear;

inline RayShear ray_shear(float3 dir) {
    const float3 a = fabs(dir);
    /* kz: axis of largest |dir|; kx, ky follow it cyclically, swapped when dir[kz] < 0 to keep
     * the winding (the test is two-sided anyway, but the sign of det stays meaningful). */
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    const float dz = kz == 0 ? dir.x : (kz == 1 ? dir.y : dir.z);
    if (dz < 0.0f) {
        const int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    const float dx = kx == 0 ? dir.x : (kx == 1 ? dir.y : dir.z);
    const float dy = ky == 0 ? dir.x : (ky == 1 ? dir.y : dir.z);
    const float sx = dx / dz, sy = dy / dz, sz = 1.0f / dz;
    /* Row 0 picks p[kx] - sx p[kz], row 1 p[ky] - sy p[kz], row 2 sz p[kz]. */
    float4 col[3];
    for (int k = 0; k < 3; ++k)
        col[k] = (float4)(k == kx ? 1.0f : (k == kz ? -sx : 0.0f), k == ky ? 1.0f : (k == kz ? -sy : 0.0f),
                          k == kz ? sz : 0.0f, 0.0f);
    RayShear s;
    s.m0 = col[0];
    s.m1 = col[1];
    s.m2 = col[2];
    return s;
}

/* A vertex in ray space. Each vertex goes through exactly the same operations in every triangle
 * that shares it, so shared edges see bitwise identical endpoints. */
inline float4 to_ray_space(float4 p, float4 org, const RayShear* s) {
    const float4 q = p - org;
    return q.x * s->m0 + q.y * s->m1 + q.z * s->m2;
}

/* Woop et al. 2013, Fig. 1 (without the double-precision fallback: an edge function that rounds
 * to exactly 0 counts as inside for both triangles sharing that edge). Accepts 0 < t < tmax.
 *
 * v1 = v0 + e1 is exact for most triangles, so shared vertices are bitwise shared and the test is
 * watertight. Where float cannot reproduce a vertex that way the host stores the largest error,
 * delta = v0.w (world units, per coordinate); such a triangle, and only such a triangle, widens
 * its edge functions by their first-order error bound |dU| <= 2 delta (|B'.xy| + |C'.xy|)
 * (a vertex moves at most delta per axis, by at most 2 delta in sheared x and y since |S| <= 1),
 * so the gap a moved vertex opens is always covered by the widened triangle. */
/* Inlined by force: as a call (PoCL's inliner declines) every leaf would spill the ray state. */
inline __attribute__((always_inline)) bool intersect_triangle(__global const float4* tris, uint prim, float4 org,
                                                              const RayShear* s, float tmax, float* t_out,
                                                              float* u_out, float* v_out) {
    const float4 v0 = tris[3 * prim], e1 = tris[3 * prim + 1], e2 = tris[3 * prim + 2];
    const float4 A = to_ray_space(v0, org, s);
    const float4 B = to_ray_space(v0 + e1, org, s); /* v0 + e1 == v1 exactly, see bvh_triangle_data */
    const float4 C = to_ray_space(v0 + e2, org, s);
    float U, V, W;
    {
        /* No fused multiply-add here: edge(P, Q) must be exactly -edge(Q, P) for shared edges. */
#pragma OPENCL FP_CONTRACT OFF
        U = C.x * B.y - C.y * B.x;
        V = A.x * C.y - A.y * C.x;
        W = B.x * A.y - B.y * A.x;
    }
    if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) {
        if (!(v0.w > 0.0f)) return false;
        const float e = 2.00001f * v0.w;
        const float a = fabs(A.x) + fabs(A.y), b = fabs(B.x) + fabs(B.y), c = fabs(C.x) + fabs(C.y);
        const float tu = e * (b + c + e), tv = e * (a + c + e), tw = e * (a + b + e);
        if (!((U >= -tu && V >= -tv && W >= -tw) || (U <= tu && V <= tv && W <= tw))) return false;
    }
    const float det = U + V + W;
    if (det == 0.0f) return false;
    const float T = U * A.z + V * B.z + W * C.z;
    /* 0 < t = T / det < tmax, tested before paying for the division. */
    const float abs_det = fabs(det), abs_T = det < 0.0f ? -T : T;
    if (!(abs_T > 0.0f) || !(abs_T < tmax * abs_det)) return false;
    const float inv_det = 1.0f / det;
    *t_out = T * inv_det;
    *u_out = V * inv_det;
    *v_out = W * inv_det;
    return *t_out > 0.0f && *t_out < tmax;
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
bool bvh_intersect(__global const BvhNode* nodes, __global const float4* tris, float3 org, float3 dir, float tmax,
                   bool any_hit, Hit* hit BVH_FILTER_PARAMS) {
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

    const RayShear shear = ray_shear(dir);
    const float4 org4 = (float4)(org, 0.0f);

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
            const bvh_floatw tfar =
                BVH_VMIN(BVH_VMIN(tfx, tfy), BVH_VMIN(tfz, (bvh_floatw)(t_best))) * BVH_FAR_SCALE;
            const int mask = bvh_lane_mask(islessequal(tnear, tfar));
            if (mask != 0) {
                int c[BVH_WIDTH];
                uint n[BVH_WIDTH];
                float d[BVH_WIDTH];
                BVH_VSTORE(BVH_AS_INTW(row[6]), 0, c);
                BVH_VSTORE(BVH_AS_UINTW(row[7]), 0, n);
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
            for (uint p = first; p < first + cur_count; ++p) {
#ifdef BVH_STATS
                ++hit->tris_tested;
#endif
                float t, u, v;
                if (intersect_triangle(tris, p, org4, &shear, t_best, &t, &u, &v) && BVH_FILTER(p, u, v)) {
                    found = true;
                    t_best = t;
                    hit->t = t;
                    hit->u = u;
                    hit->v = v;
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
