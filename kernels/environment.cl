/* environment.cl: the environment light (LIGHT_ENVIRONMENT), radiance L(w) arriving from every
 * direction w: uniform, or an equirectangular map. Orientation (docs/scenes.md): the map's top row is
 * +Y, its horizontal centre -Z (where a glTF camera with identity rotation looks), u grows
 * towards +X; theta = v pi from +Y, phi = (u - 1/2) 2 pi from -Z towards +X, so
 * w = (sin theta sin phi, cos theta, -sin theta cos phi), then turned about +Y by the light's
 * rotation (right-handed: +X towards -Z). The map is piecewise constant over its texels (nearest
 * texel), so that its sampling distribution, a 2D piecewise-constant one over (u, v) in
 * proportion to luminance times sin(theta) (as pbrt-v4's image infinite light), is exactly
 * proportional to what it samples where it matters. The host builds that distribution
 * (src/scene/environment.cpp, which holds the host reference of these functions); it lives in
 * light_cdf at the light's offset: the marginal CDF over rows (H + 1), the rows' densities over v
 * (H), then per row the conditional CDF over columns (W + 1 each) and densities over u (W each).
 * The functions take their buffers explicitly, so tests can call them without a scene. */
#ifndef CLPPM_ENVIRONMENT_CL
#define CLPPM_ENVIRONMENT_CL

#include "shared_types.h"
#include "sampling.cl"

/* The map's direction for (u, v) in [0, 1]^2, before the light's rotation. */
float3 env_direction_local(float u, float v) {
    /* theta = v pi, phi = (u - 1/2) 2 pi */
    float s = sinpi(v);
    float2 c = unit_circle(u - 0.5f);
    return (float3)(s * c.y, cospi(v), -s * c.x);
}

/* (u, v) of a direction before the light's rotation. */
float2 env_uv_local(float3 d) {
    float u = 0.5f + atan2(d.x, -d.z) * (0.5f * INV_PI_F);
    float v = acos(clamp(d.y, -1.0f, 1.0f)) * INV_PI_F;
    return (float2)(u - floor(u), v);
}

/* World from the map's frame: a turn about +Y by the light's (cos, sin). */
float3 env_to_world(__global const Light* L, float3 d) {
    float c = L->position[0], s = L->position[1];
    return (float3)(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

float3 env_from_world(__global const Light* L, float3 d) {
    float c = L->position[0], s = L->position[1];
    return (float3)(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

/* The texel (column, row) a direction in the map's frame falls in. */
uint2 env_texel(__global const Texture* t, float3 d) {
    float2 uv = env_uv_local(d);
    uint i = min((uint)(uv.x * (float)t->width), t->width - 1u);
    uint j = min((uint)(uv.y * (float)t->height), t->height - 1u);
    return (uint2)(i, j);
}

/* L(w): the radiance arriving from direction w (world, unit). */
float3 env_radiance(__global const Light* L, __global const Texture* textures, __global const float4* texels,
                    float3 w) {
    float3 scale = load3g(L->radiance);
    if (L->prim == ENV_UNIFORM) return scale;
    __global const Texture* t = &textures[L->prim];
    uint2 ij = env_texel(t, env_from_world(L, w));
    return texels[t->offset + ij.y * t->width + ij.x].xyz * scale;
}

/* The solid-angle density env_sample draws w with. */
float env_pdf(__global const Light* L, __global const Texture* textures, __global const float* light_cdf, float3 w) {
    if (L->prim == ENV_UNIFORM) return 0.25f * INV_PI_F;
    __global const Texture* t = &textures[L->prim];
    float3 d = env_from_world(L, w);
    float sin_theta = sqrt(fmax(0.0f, 1.0f - d.y * d.y));
    if (!(sin_theta > 0.0f)) return 0.0f;
    uint2 ij = env_texel(t, d);
    uint W = t->width, H = t->height;
    __global const float* row_pdf = light_cdf + L->two_sided + H + 1;
    __global const float* col_pdf = row_pdf + H + H * (W + 1);
    float p_uv = row_pdf[ij.y] * col_pdf[ij.y * W + ij.x];
    return p_uv / (2.0f * PI_F * PI_F * sin_theta);
}

/* The interval k of an increasing CDF over n intervals with cdf[k] <= u < cdf[k + 1]. */
uint cdf_interval(__global const float* cdf, uint n, float u) {
    uint lo = 0, hi = n; /* cdf[lo] <= u < cdf[hi] */
    while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1;
        if (cdf[mid] <= u) lo = mid;
        else hi = mid;
    }
    return lo;
}

/* Samples a direction w towards the environment with (u1, u2); *pdf its solid-angle density
 * (0: nothing drawn). Uniform: the whole sphere; a map: row by the marginal, column by the row's
 * conditional, uniform within the texel in (u, v). */
float3 env_sample(__global const Light* L, __global const Texture* textures, __global const float* light_cdf, float u1,
                  float u2, float* pdf) {
    if (L->prim == ENV_UNIFORM) {
        *pdf = 0.25f * INV_PI_F;
        float z = 1.0f - 2.0f * u1, r = sqrt(fmax(0.0f, 1.0f - z * z));
        float2 c = unit_circle(u2);
        return (float3)(r * c.x, z, r * c.y);
    }
    __global const Texture* t = &textures[L->prim];
    uint W = t->width, H = t->height;
    __global const float* marginal = light_cdf + L->two_sided;
    __global const float* row_pdf = marginal + H + 1;
    __global const float* cond = row_pdf + H;
    __global const float* col_pdf = cond + H * (W + 1);
    uint j = cdf_interval(marginal, H, u1);
    float dv = (u1 - marginal[j]) / fmax(marginal[j + 1] - marginal[j], 1e-30f);
    __global const float* row = cond + j * (W + 1);
    uint i = cdf_interval(row, W, u2);
    float du = (u2 - row[i]) / fmax(row[i + 1] - row[i], 1e-30f);
    float u = ((float)i + clamp(du, 0.0f, 1.0f)) / (float)W, v = ((float)j + clamp(dv, 0.0f, 1.0f)) / (float)H;
    float3 d = env_direction_local(u, v);
    float sin_theta = sqrt(fmax(0.0f, 1.0f - d.y * d.y));
    float p_uv = row_pdf[j] * col_pdf[j * W + i];
    *pdf = sin_theta > 0.0f ? p_uv / (2.0f * PI_F * PI_F * sin_theta) : 0.0f;
    return env_to_world(L, d);
}

#endif
