/* disc_coverage.cl: how much of a hit point's gather disc lies on surface that can hold the photons
 * the gather accepts. The density estimate tau / (pi R^2 N) assumes the whole disc of radius R
 * around x does. Where the surface meets a wall (a room's corners, a block standing on the floor)
 * or ends (an open edge, the top of a block), part of the disc holds no photon the gather takes,
 * and the estimate is low by that part: up to half along an edge, three quarters in a corner. This
 * bias falls only as R (bench/ERROR_CALIBRATION.md, "The photon integrators against unbiased
 * references"), and it is the one the error estimate cannot see in the photons themselves ("Two
 * bias terms for the gather disc's truncation, tried and not kept").
 *
 * The disc is measured with rays instead. In DISC_DIRECTIONS directions t_k of the tangent plane,
 * rotated at random per hit point and pass, the disc's extent e_k <= R is where
 * - a ray in the plane, DISC_PROBE_HEIGHT R above it, first meets a surface that faces away from
 *   the hit point's side (a wall or an occluder: its photons are refused), or
 * - the surface ends: the gather's ball of radius R holds no surface facing the same side along
 *   the normal through that point of the plane (a ray down the ball's chord there; tested at
 *   DISC_REACH e, and if the surface has ended, found by bisection, DISC_BISECTIONS steps). The
 *   test stops short of the extent because the chord vanishes at the rim: a surface curved by a
 *   few degrees leaves the ball only there, and a test at 0.999 R took the furnace sphere's
 *   facets for edges and left its image 5% bright.
 * The covered fraction is the polar area sum f = (1/K) sum_k (e_k / R)^2, and the gather divides
 * what it collected by f: the estimate becomes that of the covered part's own density. Inside a
 * surface f is exactly 1 and nothing changes; as R shrinks the disc leaves the edges, so the
 * estimate stays consistent. tests/disc_coverage_test.cpp holds the host reference. */
#ifndef CLPPM_DISC_COVERAGE_CL
#define CLPPM_DISC_COVERAGE_CL

#include "portability.h"
#include "rng.cl"
#include "scene.cl"
#include "hitpoint.cl"
#include "gather_common.cl"

#define DISC_DIRECTIONS 8
#define DISC_PROBE_HEIGHT 0.1f
#define DISC_BISECTIONS 3
#define DISC_REACH 0.9f
#define DISC_MIN_COVERAGE 0.125f

/* The geometric normal of triangle prim on the side facing against dir. */
float3 disc_hit_normal(SCENE_PARAMS, uint prim, float3 dir) {
    float3 e1 = tris[3 * prim + 1].xyz, e2 = tris[3 * prim + 2].xyz;
    float3 ng = normalize(cross(e1, e2));
    return dot(ng, dir) > 0.0f ? -ng : ng;
}

/* Whether a surface hit by a probe bounds the disc: light passes through a transmissive one (glass
 * standing on the floor leaves the floor under it lit), so it does not. A chord, which looks for
 * the surface that holds the photons, stops at a diffusely transmitting one too (translucent):
 * photons are stored on it (passed, a translucent block's faces all took their discs for ended,
 * and their gathers were divided by DISC_MIN_COVERAGE: eight times too bright). */
bool disc_opaque(SCENE_PARAMS, uint prim, bool translucent) {
    __global const Material* m = &materials[shading[prim].material];
    if (translucent && m->diffuse_transmission > 0.0f) return true;
    return !(m->transmission > 0.0f || m->diffuse_transmission > 0.0f);
}

/* The first opaque surface along the ray within tmax (with translucent: or diffusely transmitting,
 * disc_opaque): transmissive ones are passed (at most DISC_PASS_THROUGH of them, each left a
 * ten-thousandth of tmax behind). hit->t is from org. */
#define DISC_PASS_THROUGH 4
bool disc_trace_opaque(SCENE_PARAMS, float3 org, float3 dir, float tmax, bool translucent, Hit* hit) {
    float start = 0.0f;
    for (int k = 0; k <= DISC_PASS_THROUGH; ++k) {
        if (!trace_closest(SCENE_ARGS, org + dir * start, dir, tmax - start, hit)) return false;
        hit->t += start;
        if (disc_opaque(SCENE_ARGS, hit->prim, translucent)) return true;
        start = hit->t + 1e-4f * tmax;
        if (!(start < tmax)) return false;
    }
    return false;
}

/* Whether a surface facing the n side crosses the gather ball of radius r around p on the normal
 * through q = p + e dir (a ray down the ball's chord there, of half-length sqrt(r^2 - e^2)). */
bool disc_surface_at(SCENE_PARAMS, float3 p, float3 dir, float e, float3 n, float r) {
    const float h = sqrt(fmax(r * r - e * e, 0.0f));
    Hit hit;
    if (!disc_trace_opaque(SCENE_ARGS, p + dir * e + n * h, -n, 2.0f * h, true, &hit)) return false;
    return dot(disc_hit_normal(SCENE_ARGS, hit.prim, -n), n) > GATHER_MIN_NORMAL_COS;
}

/* The covered fraction f of the disc of radius r around p on the plane of normal n (the side the
 * hit point is seen from), with the directions rotated by u in [0, 1); and g, the covered part's
 * mean squared distance from p over that of the whole disc, r^2 / 2: the same polar sums give
 * E[d^2] = (sum_k e_k^4 / 4) / (sum_k e_k^2 / 2). The error estimate's Laplacian gather weighs
 * photons by 2 d^2 / R^2 - g, which a uniform density on the covered part sums to zero. */
float2 disc_coverage_at(SCENE_PARAMS, float3 p, float3 n, float r, float u) {
    float3 t, b;
    make_frame(n, &t, &b);
    const float h = DISC_PROBE_HEIGHT * r;
    const float3 above = p + n * h;
    float sum = 0.0f, sum4 = 0.0f;
    for (int k = 0; k < DISC_DIRECTIONS; ++k) {
        float phi = (2.0f * PI_F / DISC_DIRECTIONS) * ((float)k + u);
        float3 dir = t * cos(phi) + b * sin(phi);
        float e = r;
        Hit hit;
        /* a wall, or an occluder standing on the surface: photons there face another way */
        if (disc_trace_opaque(SCENE_ARGS, above, dir, r, false, &hit) &&
            dot(disc_hit_normal(SCENE_ARGS, hit.prim, dir), n) <= GATHER_MIN_NORMAL_COS)
            e = hit.t;
        /* the surface ends before DISC_REACH e: bisect between p (on it) and there */
        if (!disc_surface_at(SCENE_ARGS, p, dir, DISC_REACH * e, n, r)) {
            float lo = 0.0f, hi = DISC_REACH * e;
            for (int s = 0; s < DISC_BISECTIONS; ++s) {
                float mid = 0.5f * (lo + hi);
                if (disc_surface_at(SCENE_ARGS, p, dir, mid, n, r)) lo = mid;
                else hi = mid;
            }
            e = 0.5f * (lo + hi);
        }
        float q = (e / r) * (e / r);
        sum += q;
        sum4 += q * q;
    }
    return (float2)(fmax(sum / DISC_DIRECTIONS, DISC_MIN_COVERAGE), sum > 0.0f ? sum4 / sum : 1.0f);
}

/* ---- the whole disc, seen without rays --------------------------------------------------------
 * Most hit points lie well inside a surface, where disc_coverage_at's rays all find f = 1 and
 * g = 1. One query of the BVH sees that instead, from the triangles within DISC_BALL_MARGIN R of p
 * (the ball: every point a probe or a chord reaches lies within 1.005 R of p). It says whole when
 * they are all opaque, none has an open edge (src/scene/open_edges.cpp) within the ball, and either
 * - all are flat: each stays within DISC_FLAT_HEIGHT R of the tangent plane inside the ball (its
 *   plane's distance from p plus the ball's radius times the sine of its tilt from n). Flat
 *   triangles with no open edge in the ball cover the disc without a gap, and lie below the
 *   probes' height DISC_PROBE_HEIGHT R; or
 * - they form one surface over the disc, like a terrain: each faces the same way along n, at least
 *   DISC_GRAPH_COS of the way (as wound; no edge in the ball is wound against its neighbour), and
 *   stays between DISC_GRAPH_LOW R below and DISC_GRAPH_HIGH R above the tangent plane inside the
 *   ball (the lesser of its vertices' extremes and the plane bound above). Seen down n, such
 *   triangles lie side by side across every edge, so with no open edge they cover the disc as a
 *   single sheet that cannot leave the ball over it; all of it is below the probes.
 * Either way no probe meets a surface, and every chord, which runs from 0.43 R above the plane to
 * 0.43 R below it, first meets a triangle of the sheet facing the hit point's side (cosine at
 * least DISC_GRAPH_COS > GATHER_MIN_NORMAL_COS). So the rays would give exactly (1, 1), and the
 * query returns that, for about the cost of one ray instead of at least 2 DISC_DIRECTIONS. Curved
 * surfaces pass once R is small against their curvature (the sheet is about R^2 / (2 rho) high).
 * Anything else in the ball (a wall, an occluder, a transmissive surface, an open edge, a fold,
 * a T-junction) leaves the measurement to the rays. */
#define DISC_BALL_MARGIN 1.02f
#define DISC_FLAT_HEIGHT 0.05f
#define DISC_GRAPH_COS 0.15f
#define DISC_GRAPH_HIGH 0.08f
#define DISC_GRAPH_LOW 0.2f

/* Squared distance from p to triangle abc (Ericson 2005, Real-Time Collision Detection, 5.1.5). */
float disc_triangle_dist2(float3 p, float3 a, float3 b, float3 c) {
    const float3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return dot(ap, ap);
    const float3 bp = p - b;
    const float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return dot(bp, bp);
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        const float3 q = a + ab * (d1 / (d1 - d3)) - p;
        return dot(q, q);
    }
    const float3 cp = p - c;
    const float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return dot(cp, cp);
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        const float3 q = a + ac * (d2 / (d2 - d6)) - p;
        return dot(q, q);
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        const float3 q = b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))) - p;
        return dot(q, q);
    }
    const float denom = 1.0f / (va + vb + vc);
    const float3 q = a + ab * (vb * denom) + ac * (vc * denom) - p;
    return dot(q, q);
}

/* Squared distance from p to the segment ab. */
float disc_segment_dist2(float3 p, float3 a, float3 b) {
    const float3 ab = b - a;
    const float len2 = dot(ab, ab);
    const float s = len2 > 0.0f ? clamp(dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    const float3 q = a + ab * s - p;
    return dot(q, q);
}

/* Whether the disc of radius r around p on the plane of normal n lies whole on one opaque surface,
 * flat or a sheet over it, with nothing else within its ball (above). open_edges: per triangle, bit
 * k when its edge from vertex k to vertex k + 1 is open, bit 3 + k when it is wound against the
 * triangle across it. */
bool disc_is_whole(SCENE_PARAMS, __global const uchar* open_edges, float3 p, float3 n, float r) {
    const float rb = DISC_BALL_MARGIN * r, rb2 = rb * rb;
    const bvh_floatw px = (bvh_floatw)(p.x), py = (bvh_floatw)(p.y), pz = (bvh_floatw)(p.z);
    int stack_node[BVH_STACK_SIZE];
    uint stack_count[BVH_STACK_SIZE];
    int sp = 0;
    int cur = 0;
    uint cur_count = 0;
    bool found = false, all_flat = true, graph = true;
    float facing = 0.0f; /* the sign of the first triangle's cosine to n, as wound */
    for (;;) {
        if (cur >= 0) {
            /* every child whose box reaches into the ball (empty slots: an inverted box, never) */
            __global const bvh_floatw* row = (__global const bvh_floatw*)(bvh_nodes + cur);
            const bvh_floatw zero = (bvh_floatw)(0.0f);
            const bvh_floatw dx = fmax(fmax(row[0] - px, px - row[3]), zero);
            const bvh_floatw dy = fmax(fmax(row[1] - py, py - row[4]), zero);
            const bvh_floatw dz = fmax(fmax(row[2] - pz, pz - row[5]), zero);
            int mask = bvh_lane_mask(islessequal(dx * dx + dy * dy + dz * dz, (bvh_floatw)(rb2)));
            __global const int* c = (__global const int*)(row + 6);
            __global const uint* cnt = (__global const uint*)(row + 7);
            for (; mask != 0; mask &= mask - 1) {
                const int i = 31 - clz(mask & -mask);
                stack_node[sp] = c[i];
                stack_count[sp] = cnt[i];
                ++sp;
            }
        } else {
            const uint first = (uint)(~cur);
            for (uint b = first; b < first + (cur_count + BVH_TRI_BLOCK - 1) / BVH_TRI_BLOCK; ++b) {
                __global const bvh_floatb* v = (__global const bvh_floatb*)(tri_blocks + b);
                const bvh_floatb zero = (bvh_floatb)(0.0f);
                const bvh_floatb lox = fmin(fmin(v[0], v[3]), v[6]), hix = fmax(fmax(v[0], v[3]), v[6]);
                const bvh_floatb loy = fmin(fmin(v[1], v[4]), v[7]), hiy = fmax(fmax(v[1], v[4]), v[7]);
                const bvh_floatb loz = fmin(fmin(v[2], v[5]), v[8]), hiz = fmax(fmax(v[2], v[5]), v[8]);
                const bvh_floatb dx = fmax(fmax(lox - p.x, p.x - hix), zero);
                const bvh_floatb dy = fmax(fmax(loy - p.y, p.y - hiy), zero);
                const bvh_floatb dz = fmax(fmax(loz - p.z, p.z - hiz), zero);
                int lanes = bvh_block_mask(islessequal(dx * dx + dy * dy + dz * dz, (bvh_floatb)(rb2)));
                for (; lanes != 0; lanes &= lanes - 1) {
                    const int i = 31 - clz(lanes & -lanes);
                    float vf[9];
                    for (int k = 0; k < 9; ++k) vf[k] = ((__global const float*)(v + k))[i];
                    const float3 a = (float3)(vf[0], vf[1], vf[2]), bb = (float3)(vf[3], vf[4], vf[5]),
                                 cc = (float3)(vf[6], vf[7], vf[8]);
                    if (!(disc_triangle_dist2(p, a, bb, cc) <= rb2)) continue;
                    const uint prim = tri_blocks[b].prim[i];
                    if (!disc_opaque(SCENE_ARGS, prim, false)) return false;
                    if (HAS_ALPHA && materials[shading[prim].material].alpha_mode != ALPHA_OPAQUE) return false;
                    const uint edges = open_edges[prim];
                    const bool near0 = (edges & 9u) && disc_segment_dist2(p, a, bb) <= rb2;
                    const bool near1 = (edges & 18u) && disc_segment_dist2(p, bb, cc) <= rb2;
                    const bool near2 = (edges & 36u) && disc_segment_dist2(p, cc, a) <= rb2;
                    if ((near0 && (edges & 1u)) || (near1 && (edges & 2u)) || (near2 && (edges & 4u))) return false;
                    const float3 nt = cross(bb - a, cc - a);
                    const float len = length(nt), cos_tilt = dot(nt, n) / len;
                    const float sin_tilt = sqrt(fmax(1.0f - cos_tilt * cos_tilt, 0.0f));
                    const float plane = fabs(dot(a - p, nt)) / len + rb * sin_tilt; /* |height| in the ball */
                    all_flat = all_flat && plane <= DISC_FLAT_HEIGHT * r;
                    if (graph) {
                        const float ha = dot(a - p, n), hb = dot(bb - p, n), hc = dot(cc - p, n);
                        const float high = fmin(fmax(fmax(ha, hb), hc), plane);
                        const float low = fmax(fmin(fmin(ha, hb), hc), -plane);
                        if (facing == 0.0f) facing = copysign(1.0f, cos_tilt);
                        graph = cos_tilt * facing >= DISC_GRAPH_COS && high <= DISC_GRAPH_HIGH * r &&
                                low >= -DISC_GRAPH_LOW * r && !(near0 && (edges & 8u)) && !(near1 && (edges & 16u)) &&
                                !(near2 && (edges & 32u));
                    }
                    if (!all_flat && !graph) return false;
                    found = true;
                }
            }
        }
        if (sp == 0) return found;
        --sp;
        cur = stack_node[sp];
        cur_count = stack_count[sp];
    }
}

/* coverage[i] for every hit point, with this pass's radius: each hit point's own R (PPM, SPPM) or
 * PPPM's global one (global_r2 > 0). 1 where a pixel has no hit point, and for volume hit points
 * (their spheres are gathered whole). */
__kernel SCALAR_WORK_ITEMS void disc_coverage(SCENE_PARAMS, __global const uchar* open_edges,
                                              __global const HitPoint* hitpoints, __global const HitStats* stats,
                                              uint num_hitpoints, float global_r2, ulong seed, ulong pass,
                                              __global float2* coverage) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    float r2 = global_r2 > 0.0f ? global_r2 : (float)stats[i].r2;
    if (hp->pixel == HITPOINT_NONE || hitpoint_in_volume(hp) || !(r2 > 0.0f)) {
        coverage[i] = (float2)(1.0f, 1.0f);
        return;
    }
    Rng rng = rng_make(seed, pass, i, RNG_DISC_COVERAGE);
    const float3 n = oct_decode(hp->ng_oct), p = load3g(hp->pos);
    const float r = sqrt(r2);
    coverage[i] = disc_is_whole(SCENE_ARGS, open_edges, p, n, r)
                      ? (float2)(1.0f, 1.0f)
                      : disc_coverage_at(SCENE_ARGS, p, n, r, rng_float(&rng));
}

#endif
