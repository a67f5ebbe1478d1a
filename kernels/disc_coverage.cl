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
 * standing on the floor leaves the floor under it lit), so it does not. */
bool disc_opaque(SCENE_PARAMS, uint prim) {
    __global const Material* m = &materials[shading[prim].material];
    return !(m->transmission > 0.0f || m->diffuse_transmission > 0.0f);
}

/* The first opaque surface along the ray within tmax: transmissive ones are passed (at most
 * DISC_PASS_THROUGH of them, each left a ten-thousandth of tmax behind). hit->t is from org. */
#define DISC_PASS_THROUGH 4
bool disc_trace_opaque(SCENE_PARAMS, float3 org, float3 dir, float tmax, Hit* hit) {
    float start = 0.0f;
    for (int k = 0; k <= DISC_PASS_THROUGH; ++k) {
        if (!trace_closest(SCENE_ARGS, org + dir * start, dir, tmax - start, hit)) return false;
        hit->t += start;
        if (disc_opaque(SCENE_ARGS, hit->prim)) return true;
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
    if (!disc_trace_opaque(SCENE_ARGS, p + dir * e + n * h, -n, 2.0f * h, &hit)) return false;
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
        if (disc_trace_opaque(SCENE_ARGS, above, dir, r, &hit) &&
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

/* coverage[i] for every hit point, with this pass's radius: each hit point's own R (PPM, SPPM) or
 * PPPM's global one (global_r2 > 0). 1 where a pixel has no hit point. */
__kernel void disc_coverage(SCENE_PARAMS, __global const HitPoint* hitpoints, __global const HitStats* stats,
                            uint num_hitpoints, float global_r2, ulong seed, ulong pass, __global float2* coverage) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    float r2 = global_r2 > 0.0f ? global_r2 : (float)stats[i].r2;
    if (hp->pixel == HITPOINT_NONE || !(r2 > 0.0f)) {
        coverage[i] = (float2)(1.0f, 1.0f);
        return;
    }
    Rng rng = rng_make(seed, pass, i, RNG_DISC_COVERAGE);
    float3 n = oct_decode(hp->ng_oct);
    coverage[i] = disc_coverage_at(SCENE_ARGS, load3g(hp->pos), n, sqrt(r2), rng_float(&rng));
}

#endif
