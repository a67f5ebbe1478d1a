/* texture.cl: glTF texture sampling, bilinear between texel centres with REPEAT or
 * CLAMP_TO_EDGE per axis (src/scene/texture_sampling.cpp is the host reference). */
#ifndef CLPPM_TEXTURE_CL
#define CLPPM_TEXTURE_CL

#include "shared_types.h"

/* A texture coordinate reduced before it is scaled to texels, so that any value (a huge finite
 * one, or one whose interpolation overflowed) gives texel indices in range: repeat keeps the
 * fraction, clamp-to-edge keeps [-1, 2], beyond which every bilinear tap clamps alike. */
float wrap_coordinate(float u, bool clamp_to_edge) {
    if (!isfinite(u)) u = 0.0f;
    return clamp_to_edge ? clamp(u, -1.0f, 2.0f) : u - floor(u);
}

/* Linear RGBA of texture `index` at uv. */
float4 texture_rgba(__global const Texture* textures, __global const float4* texels, int index, float2 uv) {
    __global const Texture* tex = &textures[index];
    float w = (float)tex->width, hgt = (float)tex->height;
    float x = wrap_coordinate(uv.x, tex->wrap & 1u) * w - 0.5f, y = wrap_coordinate(uv.y, tex->wrap & 2u) * hgt - 0.5f;
    float fx = floor(x), fy = floor(y);
    float ax = x - fx, ay = y - fy;
    int ix = (int)fx, iy = (int)fy;
    float4 acc = (float4)(0.0f);
    for (int k = 0; k < 4; ++k) {
        int px = ix + (k & 1), py = iy + (k >> 1);
        if (tex->wrap & 1u) px = clamp(px, 0, (int)tex->width - 1);
        else px = ((px % (int)tex->width) + (int)tex->width) % (int)tex->width;
        if (tex->wrap & 2u) py = clamp(py, 0, (int)tex->height - 1);
        else py = ((py % (int)tex->height) + (int)tex->height) % (int)tex->height;
        float wx = (k & 1) ? ax : 1.0f - ax, wy = (k >> 1) ? ay : 1.0f - ay;
        acc += texels[tex->offset + (uint)py * tex->width + (uint)px] * (wx * wy);
    }
    return acc;
}

#endif
