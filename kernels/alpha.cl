/* alpha.cl: glTF alphaMode (Sec. 3.9.4) as ray visibility. Coverage is the base colour's alpha:
 * baseColorFactor[3] x baseColorTexture alpha x COLOR_0 alpha. MASK: a surface exists where
 * coverage >= alphaCutoff; BLEND: stochastic transparency, an intersection counts with
 * probability equal to the coverage (a hash of the ray and the triangle, uniform in [0, 1),
 * decides), so that light through a blended surface is right in expectation. Rays of every kind
 * (camera, photon, shadow) test it alike, in the traversal (bvh_traverse.cl's BVH_FILTER hook),
 * and a scene without alpha never compiles it (HAS_ALPHA). */
#ifndef CLPPM_ALPHA_CL
#define CLPPM_ALPHA_CL

#include "kernel_features.h"
#include "shared_types.h"
#include "texture.cl"

#if HAS_ALPHA

/* A uniform number in [0, 1) from the ray and the triangle: the same for the same ray and
 * triangle (so closest-hit and any-hit agree), independent between rays. */
float alpha_hash(float3 org, float3 dir, uint prim) {
    uint h = prim * 0x9E3779B9u;
    h ^= as_uint(org.x) + 0x85EBCA6Bu + (h << 6) + (h >> 2);
    h ^= as_uint(org.y) + 0xC2B2AE35u + (h << 6) + (h >> 2);
    h ^= as_uint(org.z) + 0x27D4EB2Fu + (h << 6) + (h >> 2);
    h ^= as_uint(dir.x) + 0x165667B1u + (h << 6) + (h >> 2);
    h ^= as_uint(dir.y) + 0xD3A2646Cu + (h << 6) + (h >> 2);
    h ^= as_uint(dir.z) + 0xFD7046C5u + (h << 6) + (h >> 2);
    /* murmur3's finaliser */
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    h ^= h >> 16;
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

/* Whether the intersection at barycentrics (u, v) of triangle prim counts for a ray (org, dir). */
bool alpha_covers(__global const TriShading* shading, __global const Material* materials,
                  __global const Texture* textures, __global const float4* texels, __global const float4* colors,
                  __global const float2* uv1, __constant SceneInfo* info, uint prim, float u, float v, float3 org,
                  float3 dir) {
    __global const TriShading* sh = &shading[prim];
    __global const Material* m = &materials[sh->material];
    if (m->alpha_mode == ALPHA_OPAQUE) return true;
    float w = 1.0f - u - v;
    float a = m->base_color[3];
    if (m->base_color_tex >= 0) {
        float2 t0 = (float2)(sh->uv0[0], sh->uv0[1]) * w + (float2)(sh->uv1[0], sh->uv1[1]) * u +
                    (float2)(sh->uv2[0], sh->uv2[1]) * v;
        float2 t1 = info->texcoord1 ? uv1[3 * prim] * w + uv1[3 * prim + 1] * u + uv1[3 * prim + 2] * v : t0;
        a *= texture_rgba(textures, texels, m->base_color_tex, (float4)(t0, t1)).w;
    }
    if (info->vertex_colors) a *= colors[3 * prim].w * w + colors[3 * prim + 1].w * u + colors[3 * prim + 2].w * v;
    if (m->alpha_mode == ALPHA_MASK) return a >= m->alpha_cutoff;
    return alpha_hash(org, dir, prim) < a;
}

#define BVH_FILTER_PARAMS                                                                                              \
    , __global const TriShading *shading, __global const Material *materials, __global const Texture *textures,        \
        __global const float4 *texels, __global const float4 *colors, __global const float2 *uv1,                      \
        __constant SceneInfo *info
#define BVH_FILTER_ARGS , shading, materials, textures, texels, colors, uv1, info
#define BVH_FILTER(prim, u, v)                                                                                         \
    alpha_covers(shading, materials, textures, texels, colors, uv1, info, prim, u, v, org, dir)

#endif

#endif
