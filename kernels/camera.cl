/* camera.cl: primary rays, pinhole, thin lens or orthographic, starting at the clip plane znear
 * (glTF's near plane: what lies nearer to the camera is not seen, as viewers and Blender clip it). */
#ifndef CLPPM_CAMERA_CL
#define CLPPM_CAMERA_CL

#include "shared_types.h"
#include "sampling.cl"
#include "rng.cl" /* pixel_sample_offset */

bool camera_orthographic(__constant Camera* cam) { return HAS_ORTHOGRAPHIC && cam->forward[3] != 0.0f; }

/* Ray through image position (px, py) in pixels, y down. lens_u in [0,1)^2 picks the lens point. */
void camera_ray(__constant Camera* cam, float px, float py, float2 lens_u, float3* org, float3* dir) {
    float sx = 2.0f * px / (float)cam->width - 1.0f;
    float sy = 1.0f - 2.0f * py / (float)cam->height;
    float znear = cam->origin[3];
    if (camera_orthographic(cam)) { /* parallel rays from the image rectangle through the origin */
        float3 f = load3c(cam->forward);
        *org = load3c(cam->origin) + load3c(cam->right) * sx + load3c(cam->up) * sy + f * znear;
        *dir = f;
        return;
    }
    float3 d = load3c(cam->forward) + load3c(cam->right) * sx + load3c(cam->up) * sy;
    float3 o = load3c(cam->origin);
    if (HAS_THIN_LENS && cam->lens_radius > 0.0f) {
        /* Thin lens: all rays through a pixel meet on the plane of focus (pbrt-v4 PerspectiveCamera). */
        float3 focus = o + d * cam->focus_distance;
        float r = cam->lens_radius * sqrt(lens_u.x);
        float2 c = unit_circle(lens_u.y);
        float3 right = normalize(load3c(cam->right)), up = normalize(load3c(cam->up));
        o = o + right * (r * c.x) + up * (r * c.y);
        d = focus - o;
    }
    d = normalize(d);
    /* The lens point lies in the plane through the origin across the view axis. */
    *org = znear > 0.0f ? o + d * (znear / dot(d, load3c(cam->forward))) : o;
    *dir = d;
}

/* The width of one pixel's footprint at path length t from the camera (the initial radius
 * heuristics): t times the angle one pixel subtends, or the pixel's own width when orthographic. */
float camera_footprint(__constant Camera* cam, float t) {
    float pixel = 2.0f * length(load3c(cam->up)) / (float)cam->height;
    return camera_orthographic(cam) ? pixel : t * pixel;
}

/* The solid-angle density with which one pixel's uniform sample draws a ray at cos_theta to the
 * view axis: 1 / (A_pix cos^3), A_pix the pixel's area on the image plane at distance 1
 * (SmallVCM's imageToSolidAngleFactor for a pixel of unit area). The same from any point of a thin
 * lens: the pixel maps onto the plane of focus scaled by the focus distance, which cancels. */
float camera_pixel_pdf_w(__constant Camera* cam, float cos_theta) {
    float a_pix =
        4.0f * length(load3c(cam->right)) * length(load3c(cam->up)) / ((float)cam->width * (float)cam->height);
    return 1.0f / (a_pix * cos_theta * cos_theta * cos_theta);
}

/* Where the camera sees point x through the lens point lens_u picks (camera_ray's lens sampling;
 * the pinhole: its centre): false when x is behind the lens or off the image; else the pixel,
 * cos_theta between the view axis and the ray from the lens point to x, and that lens point (eye).
 * camera_ray's inverse: the ray meets the plane of focus where the pixel's rays do. */
bool camera_project(__constant Camera* cam, float3 x, float2 lens_u, uint* pixel, float* cos_theta, float3* eye) {
    float3 o = load3c(cam->origin), f = load3c(cam->forward);
    float3 r = load3c(cam->right), u = load3c(cam->up);
    float3 e = o;
    bool lens = HAS_THIN_LENS && cam->lens_radius > 0.0f;
    if (lens) {
        float rad = cam->lens_radius * sqrt(lens_u.x);
        float2 c = unit_circle(lens_u.y);
        e = o + normalize(r) * (rad * c.x) + normalize(u) * (rad * c.y);
    }
    float3 d = x - e;
    float len = length(d);
    if (!(len > 0.0f)) return false;
    d /= len;
    float c = dot(d, f);
    if (!(c > 0.0f) || !(len * c > cam->origin[3])) return false; /* behind the lens or nearer than znear */
    /* The image-plane direction at distance 1 (camera_ray's d): through the lens point to the
     * plane of focus, then back from the lens centre. */
    float3 q = lens ? (e + d * (cam->focus_distance / c) - o) / cam->focus_distance : d / c;
    float sx = dot(q, r) / dot(r, r), sy = dot(q, u) / dot(u, u);
    float px = (sx + 1.0f) * 0.5f * (float)cam->width, py = (1.0f - sy) * 0.5f * (float)cam->height;
    if (!(px >= 0.0f && px < (float)cam->width && py >= 0.0f && py < (float)cam->height)) return false;
    *pixel = min((uint)py, cam->height - 1u) * cam->width + min((uint)px, cam->width - 1u);
    *cos_theta = c;
    *eye = e;
    return true;
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
