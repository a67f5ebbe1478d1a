/* texture.cl: glTF texture sampling, bilinear between texel centres or (magFilter NEAREST) the
 * texel a coordinate falls in, with REPEAT, MIRRORED_REPEAT or CLAMP_TO_EDGE per axis
 * (src/scene/texture_sampling.cpp is the host reference). */
#ifndef CLPPM_TEXTURE_CL
#define CLPPM_TEXTURE_CL

#include "shared_types.h"

/* A texture coordinate reduced before it is scaled to texels, so that any value (a huge finite
 * one, or one whose interpolation overflowed) gives texel indices in range: repeat keeps the
 * fraction, mirrored repeat the position in [0, 2), clamp-to-edge keeps [-1, 2], beyond which
 * every bilinear tap clamps alike. */
float wrap_coordinate(float u, bool clamp_to_edge, bool mirror) {
    if (!isfinite(u)) u = 0.0f;
    if (clamp_to_edge) return clamp(u, -1.0f, 2.0f);
    return mirror ? u - 2.0f * floor(0.5f * u) : u - floor(u);
}

/* A bilinear tap's texel index along an axis of n texels. Mirrored repeat reflects at every
 * edge: ..., 1, 0 | 0, 1, ..., n-1 | n-1, ... */
int wrap_texel(int i, int n, bool clamp_to_edge, bool mirror) {
    if (clamp_to_edge) return clamp(i, 0, n - 1);
    if (mirror) {
        int m = ((i % (2 * n)) + 2 * n) % (2 * n);
        return m < n ? m : 2 * n - 1 - m;
    }
    return ((i % n) + n) % n;
}

/* Linear RGBA of texture `index` at the surface's texture coordinates uv (xy: TEXCOORD_0,
 * zw: TEXCOORD_1): the texture's set, through its KHR_texture_transform. */
float4 texture_rgba(__global const Texture* textures, __global const float4* texels, int index, float4 uv) {
    __global const Texture* tex = &textures[index];
    float2 st = tex->texcoord ? uv.zw : uv.xy;
    __global const float* m = tex->xform;
    st = (float2)(m[0] * st.x + m[1] * st.y + m[2], m[3] * st.x + m[4] * st.y + m[5]);
    const bool cs = (tex->wrap & TEXTURE_CLAMP_S) != 0u, ct = (tex->wrap & TEXTURE_CLAMP_T) != 0u;
    const bool ms = (tex->wrap & TEXTURE_MIRROR_S) != 0u, mt = (tex->wrap & TEXTURE_MIRROR_T) != 0u;
    const int w = (int)tex->width, h = (int)tex->height;
    const float rs = wrap_coordinate(st.x, cs, ms), rt = wrap_coordinate(st.y, ct, mt);
    if (tex->wrap & TEXTURE_NEAREST) {
        int px = wrap_texel((int)floor(rs * (float)w), w, cs, ms),
            py = wrap_texel((int)floor(rt * (float)h), h, ct, mt);
        return texels[tex->offset + (uint)py * tex->width + (uint)px];
    }
    float x = rs * (float)w - 0.5f, y = rt * (float)h - 0.5f;
    float fx = floor(x), fy = floor(y);
    float ax = x - fx, ay = y - fy;
    int ix = (int)fx, iy = (int)fy;
    float4 acc = (float4)(0.0f);
    for (int k = 0; k < 4; ++k) {
        int px = wrap_texel(ix + (k & 1), w, cs, ms), py = wrap_texel(iy + (k >> 1), h, ct, mt);
        float wx = (k & 1) ? ax : 1.0f - ax, wy = (k >> 1) ? ay : 1.0f - ay;
        acc += texels[tex->offset + (uint)py * tex->width + (uint)px] * (wx * wy);
    }
    return acc;
}

#endif
