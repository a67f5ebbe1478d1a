/* scene.cl: the scene buffers every kernel receives, and what a ray hit means: the surface
 * (position, normals, texture coordinates, material) and the material's colours there. */
#ifndef CLPPM_SCENE_CL
#define CLPPM_SCENE_CL

#include "shared_types.h"
#include "sampling.cl"
#include "texture.cl"
#include "alpha.cl"
#include "bvh_traverse.cl"

/* One spelling of the scene arguments for kernels and the functions they call. */
#define SCENE_PARAMS                                                                                                   \
    __global const BvhNode *bvh_nodes, __global const BvhTriBlock *tri_blocks, __global const float4 *tris,            \
        __global const TriShading *shading, __global const Material *materials, __global const Texture *textures,      \
        __global const float4 *texels, __global const float4 *tangents, __global const float4 *colors,                 \
        __global const float2 *uv1, __global const Light *lights, __global const float *light_cdf,                     \
        __constant SceneInfo *info
#define SCENE_ARGS                                                                                                     \
    bvh_nodes, tri_blocks, tris, shading, materials, textures, texels, tangents, colors, uv1, lights, light_cdf, info

typedef struct {
    float3 p;
    float3 ng; /* geometric normal, on the side the ray came from */
    float3 ns; /* shading normal, on the same side */
    float3 nl; /* the smooth normal: ns before the normal map (= ns without one), same side */
    float3 nc; /* KHR_materials_clearcoat: the coat's normal (its own map's, else nl), same side */
    float3 ta; /* KHR_materials_anisotropy: the unit direction of the stretched GGX, across ns */
    float4 uv; /* xy: TEXCOORD_0, zw: TEXCOORD_1 (= TEXCOORD_0 when the scene has none) */
    uint material;
    uint prim;
    bool front; /* the ray arrived on the side the winding (glTF counter-clockwise) normal faces */
    float t;
    float4 color; /* COLOR_0 interpolated (linear RGBA), 1 without vertex colours */
} Surface;

bool trace_closest(SCENE_PARAMS, float3 org, float3 dir, float tmax, Hit* hit) {
    return bvh_intersect(bvh_nodes, tri_blocks, org, dir, tmax, false, hit BVH_FILTER_ARGS);
}

bool trace_occluded(SCENE_PARAMS, float3 org, float3 dir, float tmax) {
    Hit hit;
    return bvh_intersect(bvh_nodes, tri_blocks, org, dir, tmax, true, &hit BVH_FILTER_ARGS);
}

/* Offset along the normal on the side the next ray leaves from, scaled with the scene and with
 * the magnitude of the position (float spacing grows with |p|). */
float3 offset_origin(SCENE_PARAMS, float3 p, float3 n_side) {
    float m = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
    return p + n_side * (info->ray_eps + 4e-6f * m);
}

float3 texture_lookup(SCENE_PARAMS, int index, float4 uv);

/* glTF normalTexture (Sec. 3.9.3): the map's normal, (texel * 2 - 1) with x and y times scale,
 * in the frame (t, b, n) of triangle prim at barycentrics (b1, b2): n the interpolated shading
 * normal, t the interpolated tangent made orthogonal to n, b = cross(n, t) w. A corner without
 * a tangent (zero) leaves n as it is. tex and scale: the material's normalTexture, or its
 * clearcoatNormalTexture. */
float3 normal_mapped(SCENE_PARAMS, int tex, float scale, uint prim, float b1, float b2, float3 n, float4 uv) {
    float4 t4 = tangents[3 * prim] * (1.0f - b1 - b2) + tangents[3 * prim + 1] * b1 + tangents[3 * prim + 2] * b2;
    float3 t = t4.xyz - n * dot(n, t4.xyz);
    float len = length(t);
    if (!(len > 1e-12f)) return n;
    t /= len;
    float3 b = cross(n, t) * (t4.w < 0.0f ? -1.0f : 1.0f);
    float3 c = texture_lookup(SCENE_ARGS, tex, uv) * 2.0f - 1.0f;
    float3 v = t * (c.x * scale) + b * (c.y * scale) + n * c.z;
    float l = length(v);
    return (l > 1e-12f && isfinite(l)) ? v / l : n;
}

/* Texture coordinates at barycentrics (b1, b2) of triangle prim: TEXCOORD_0 in xy, TEXCOORD_1
 * in zw (a copy of TEXCOORD_0 when the scene has no second set). */
float4 triangle_uv(SCENE_PARAMS, uint prim, float b1, float b2) {
    __global const TriShading* sh = &shading[prim];
    float b0 = 1.0f - b1 - b2;
    float2 t0 = (float2)(sh->uv0[0], sh->uv0[1]) * b0 + (float2)(sh->uv1[0], sh->uv1[1]) * b1 +
                (float2)(sh->uv2[0], sh->uv2[1]) * b2;
    float2 t1 = t0;
    if (HAS_TEXTURES && info->texcoord1) t1 = uv1[3 * prim] * b0 + uv1[3 * prim + 1] * b1 + uv1[3 * prim + 2] * b2;
    return (float4)(t0.x, t0.y, t1.x, t1.y); /* oclgrind 21.10's --uninitialized crashes on (t0, t1) */
}

/* KHR_materials_anisotropy: the direction the GGX lobe stretches along, in the tangent plane of
 * the shading normal n: the interpolated tangent frame's (t, b = cross(n, t) w) direction
 * anisotropyTexture.rg * 2 - 1 (else (1, 0)), turned by anisotropyRotation from t towards b. A
 * triangle without tangents (no TEXCOORD_0) takes an arbitrary frame about n. */
float3 anisotropy_direction(SCENE_PARAMS, __global const Material* m, uint prim, float b1, float b2, float3 n,
                            float4 uv) {
    float4 t4 = tangents[3 * prim] * (1.0f - b1 - b2) + tangents[3 * prim + 1] * b1 + tangents[3 * prim + 2] * b2;
    float3 t = t4.xyz - n * dot(n, t4.xyz), b;
    float len = length(t);
    if (len > 1e-12f && isfinite(len)) {
        t /= len;
        b = cross(n, t) * (t4.w < 0.0f ? -1.0f : 1.0f);
    } else {
        make_frame(n, &t, &b);
    }
    float2 d = (float2)(1.0f, 0.0f);
    if (HAS_TEXTURES && m->anisotropy_tex >= 0) {
        float2 c = texture_rgba(textures, texels, m->anisotropy_tex, uv).xy * 2.0f - 1.0f;
        if (dot(c, c) > 1e-12f) d = normalize(c);
    }
    float cr = cos(m->anisotropy_rotation), sr = sin(m->anisotropy_rotation);
    float3 a = t * (cr * d.x - sr * d.y) + b * (sr * d.x + cr * d.y);
    a -= n * dot(n, a);
    float l = length(a);
    if (!(l > 1e-12f)) {
        make_frame(n, &t, &b);
        return t;
    }
    return a / l;
}

Surface make_surface(SCENE_PARAMS, float3 dir, const Hit* h) {
    Surface s;
    uint prim = h->prim;
    float3 v0 = tris[3 * prim].xyz, e1 = tris[3 * prim + 1].xyz, e2 = tris[3 * prim + 2].xyz;
    float b1 = h->u, b2 = h->v, b0 = 1.0f - b1 - b2;
    s.p = v0 + e1 * b1 + e2 * b2;
    s.t = h->t;
    s.prim = prim;
    float3 ng = normalize(cross(e1, e2));
    __global const TriShading* sh = &shading[prim];
    float3 ns = load3g(sh->n0) * b0 + load3g(sh->n1) * b1 + load3g(sh->n2) * b2;
    float len = length(ns);
    ns = (len > 1e-12f && isfinite(len)) ? ns / len : ng;
    /* Texture coordinates only where a texture reads them (scene_features.cpp sets HAS_TEXTURES
     * for every textured input, normal maps included). */
    s.uv = HAS_TEXTURES ? triangle_uv(SCENE_ARGS, prim, b1, b2) : (float4)(0.0f);
    s.material = sh->material;
    s.color = (HAS_VERTEX_COLORS && info->vertex_colors)
                  ? colors[3 * prim] * b0 + colors[3 * prim + 1] * b1 + colors[3 * prim + 2] * b2
                  : (float4)(1.0f);
    float3 nl = ns;
    __global const Material* m = &materials[s.material];
    float3 nc = nl;
    if (HAS_CLEARCOAT && HAS_NORMAL_MAPS && m->clearcoat > 0.0f && m->clearcoat_normal_tex >= 0)
        nc = normal_mapped(SCENE_ARGS, m->clearcoat_normal_tex, m->clearcoat_normal_scale, prim, b1, b2, nl, s.uv);
    if (HAS_NORMAL_MAPS && m->normal_tex >= 0)
        ns = normal_mapped(SCENE_ARGS, m->normal_tex, m->normal_scale, prim, b1, b2, ns, s.uv);
    s.front = dot(ng, dir) < 0.0f;
    if (!s.front) {
        ng = -ng;
        ns = -ns;
        nl = -nl;
        nc = -nc;
    }
    /* An interpolated normal facing away from the ray would make shading inconsistent. */
    if (dot(ns, dir) >= 0.0f) ns = ng;
    if (dot(nl, dir) >= 0.0f) nl = ng;
    if (dot(nc, dir) >= 0.0f) nc = ng;
    s.ng = ng;
    s.ns = ns;
    s.nl = HAS_NORMAL_MAPS ? nl : ns;
    s.nc = HAS_CLEARCOAT ? nc : s.nl;
    s.ta = (float3)(0.0f);
    if (HAS_ANISOTROPY && m->anisotropy_strength > 0.0f)
        s.ta = anisotropy_direction(SCENE_ARGS, m, prim, b1, b2, ns, s.uv);
    return s;
}

float3 texture_lookup(SCENE_PARAMS, int index, float4 uv) { return texture_rgba(textures, texels, index, uv).xyz; }

/* Base colour at the surface: factor times texture times COLOR_0 (linear). */
float3 surface_base_color(SCENE_PARAMS, const Surface* s) {
    __global const Material* m = &materials[s->material];
    float3 c = load3g(m->base_color);
    if (HAS_TEXTURES && m->base_color_tex >= 0) c *= texture_lookup(SCENE_ARGS, m->base_color_tex, s->uv);
    if (HAS_VERTEX_COLORS) c *= s->color.xyz;
    return c;
}

/* KHR_materials_unlit: what an unlit surface shows, its base colour as it is (factor, texture
 * and COLOR_0), to camera rays and to chains of delta bounces from the camera (a mirror's or
 * smooth glass's image of it); zero for any other surface. Such a surface scatters nothing
 * (surface_bsdf gives it no lobe): it lights nothing, gathers nothing and ends every path. */
bool surface_is_unlit(SCENE_PARAMS, const Surface* s) {
    return HAS_UNLIT && (materials[s->material].flags & MATERIAL_FLAG_UNLIT) != 0u;
}

float3 surface_unlit(SCENE_PARAMS, const Surface* s) {
    return surface_is_unlit(SCENE_ARGS, s) ? surface_base_color(SCENE_ARGS, s) : (float3)(0.0f);
}

/* Which closed volume the ray that found the surface s arrived through: the mesh's own (its
 * material's index + 1) on the back face of a mesh that encloses a volume
 * (MATERIAL_FLAG_ENCLOSES_VOLUME), else the one the mesh lies in (Material.outside, 0: the world's;
 * src/scene/volume_nesting.h). kernels/medium.cl tells segments so. */
uint surface_arrival_volume(SCENE_PARAMS, const Surface* s) {
    __global const Material* m = &materials[s->material];
    return (m->flags & MATERIAL_FLAG_ENCLOSES_VOLUME) && !s->front ? s->material + 1u : m->outside;
}

/* KHR_materials_volume: the fraction of light that survives the segment of length dist a ray
 * travelled inside a closed mesh of an absorbing material to reach s (surface_arrival_volume), by
 * Beer-Lambert's law exp(-sigma dist). 1 elsewhere. */
float3 volume_transmittance(SCENE_PARAMS, const Surface* s, float dist) {
    if (!HAS_VOLUME) return (float3)(1.0f);
    const uint v = surface_arrival_volume(SCENE_ARGS, s);
    if (v == 0u) return (float3)(1.0f);
    float3 sigma = load3g(materials[v - 1u].attenuation);
    if (!(max3(sigma) > 0.0f)) return (float3)(1.0f);
    return exp(-sigma * dist);
}

/* Emitted radiance: the emission factor times the emissive texture (sRGB decoded) at uv. */
float3 material_emission(SCENE_PARAMS, uint material, float4 uv) {
    __global const Material* m = &materials[material];
    float3 le = load3g(m->emission);
    if (HAS_TEXTURES && m->emissive_tex >= 0) le *= texture_lookup(SCENE_ARGS, m->emissive_tex, uv);
    return le;
}

/* An area light's spread (Blender's, as Cycles models it: a soft box's grid of slats, D10594):
 * the radiance at angle a from the emitting side's normal is scaled by
 * f(a) = max(tan h - tan a, 0) / (tan h - h), h half the spread, which keeps the Lambertian
 * emitter's power: int f cos dw over the hemisphere = pi (so light powers, light choice and the
 * cosine-distributed emission pdfs stay as they are; photons carry f in their flux). t = tan h,
 * 0 for none (f = 1). */
float emission_spread_factor(float t, float cos_a) {
    if (!HAS_EMISSION_SPREAD || !(t > 0.0f)) return 1.0f;
    if (!(cos_a > 0.0f)) return 0.0f;
    float tan_a = sqrt(fmax(0.0f, 1.0f - cos_a * cos_a)) / cos_a;
    float h = atan(t);
    /* tan h - h, by its series where it cancels in float: h^3/3 + 2h^5/15 */
    float norm = h > 0.05f ? t - h : h * h * h * (1.0f / 3.0f + h * h * (2.0f / 15.0f));
    return fmax(t - tan_a, 0.0f) / norm;
}

/* Emitted radiance towards the ray (direction dir, not necessarily unit): from the front face,
 * or both faces when double-sided; an area light's spread narrows it. */
float3 surface_emission(SCENE_PARAMS, const Surface* s, float3 dir) {
    __global const Material* m = &materials[s->material];
    if (!s->front && !(m->flags & MATERIAL_FLAG_DOUBLE_SIDED)) return (float3)(0.0f);
    float3 le = material_emission(SCENE_ARGS, s->material, s->uv);
    if (HAS_EMISSION_SPREAD && m->emission_spread > 0.0f)
        le *= emission_spread_factor(m->emission_spread, -dot(normalize(dir), s->ng));
    return le;
}

#endif
