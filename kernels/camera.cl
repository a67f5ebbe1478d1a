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
    if (cam->lens_radius > 0.0f) {
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

/* Sub-pixel offset of sample `s` of `spp`: pixel centre for one sample, else stratified jitter. */
float2 pixel_sample_offset(uint s, uint spp, Rng* rng) {
    if (spp == 1) return (float2)(0.5f, 0.5f);
    uint n = (uint)ceil(sqrt((float)spp));
    uint sx = s % n, sy = (s / n) % n;
    return (float2)(((float)sx + rng_float(rng)) / (float)n, ((float)sy + rng_float(rng)) / (float)n);
}

#endif
