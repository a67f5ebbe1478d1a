/* camera.cl: primary rays, pinhole or thin lens. */
#ifndef CLPPM_CAMERA_CL
#define CLPPM_CAMERA_CL

#include "shared_types.h"
#include "sampling.cl"

/* Ray through image position (px, py) in pixels, y down. lens_u in [0,1)^2 picks the lens point. */
void camera_ray(__constant Camera* cam, float px, float py, float2 lens_u, float3* org, float3* dir) {
    float sx = 2.0f * px / (float)cam->width - 1.0f;
    float sy = 1.0f - 2.0f * py / (float)cam->height;
    float3 d = load3c(cam->forward) + load3c(cam->right) * sx + load3c(cam->up) * sy;
    float3 o = load3c(cam->origin);
    if (HAS_THIN_LENS && cam->lens_radius > 0.0f) {
        /* Thin lens: all rays through a pixel meet on the plane of focus (pbrt-v4 PerspectiveCamera). */
        float3 focus = o + d * cam->focus_distance;
        float r = cam->lens_radius * sqrt(lens_u.x), phi = 2.0f * PI_F * lens_u.y;
        float3 right = normalize(load3c(cam->right)), up = normalize(load3c(cam->up));
        o = o + right * (r * cos(phi)) + up * (r * sin(phi));
        d = focus - o;
    }
    *org = o;
    *dir = normalize(d);
}

/* The pixel filter by importance sampling (filter importance sampling: every sample weighs the
 * same): box (default) over the pixel, or with -DPIXEL_FILTER_TENT a separable tent of radius one
 * pixel around its centre, through the inverse of its CDF. u in [0,1) -> offset from the pixel's
 * left/top edge. */
float filter_warp(float u) {
#ifdef PIXEL_FILTER_TENT
    float x = u < 0.5f ? sqrt(2.0f * u) - 1.0f : 1.0f - sqrt(2.0f * (1.0f - u));
    return 0.5f + x;
#else
    return u;
#endif
}

/* Sub-pixel offset of sample `s` of `spp`. Fixed hit points (PPM) with one sample per pixel take
 * the pixel centre; otherwise strata of the unit square are jittered and warped by the filter.
 * `stochastic` (SPPM/PPPM: a new sample every pass) jitters even a single sample. */
float2 pixel_sample_offset(uint s, uint spp, bool stochastic, Rng* rng) {
    if (spp == 1 && !stochastic) return (float2)(0.5f, 0.5f);
    uint n = (uint)ceil(sqrt((float)spp));
    uint sx = s % n, sy = (s / n) % n;
    float2 u = (float2)(((float)sx + rng_float(rng)) / (float)n, ((float)sy + rng_float(rng)) / (float)n);
    return (float2)(filter_warp(u.x), filter_warp(u.y));
}

#endif
