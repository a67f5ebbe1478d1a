/* bsdf.cl: the specular events of the clppm material model (glTF mapping in README.md):
 * perfect mirror, smooth dielectric with exact Fresnel, and the choice between them. */
#ifndef CLPPM_BSDF_CL
#define CLPPM_BSDF_CL

#include "scene.cl"
#include "ggx.cl"

/* Glossy surfaces at least this rough (GGX alpha = roughness^2) get hit points and are gathered
 * with their BRDF; smoother ones are importance-sampled through like mirrors, where a density
 * estimate would blur the reflection. */
#define GLOSSY_HITPOINT_ALPHA 0.04f

/* Unpolarised Fresnel reflectance for a dielectric; cos_i > 0 on the incident side and eta the
 * relative index n_t / n_i (pbrt-v4 FrDielectric). Returns 1 under total internal reflection. */
float fresnel_dielectric(float cos_i, float eta) {
    cos_i = clamp(cos_i, 0.0f, 1.0f);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;
    float cos_t = sqrt(1.0f - sin2_t);
    float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

float3 reflect_dir(float3 d, float3 n) { return d - 2.0f * dot(d, n) * n; }

/* Refraction of incoming direction d (pointing at the surface) through normal n (facing against
 * d), relative index eta = n_t / n_i. Valid only when fresnel_dielectric < 1. */
float3 refract_dir(float3 d, float3 n, float eta) {
    float cos_i = -dot(d, n);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    return normalize(d / eta + (cos_i / eta - cos_t) * n);
}

/* Mirror reflection about the shading normal, falling back to the geometric normal when the
 * shading normal would send the ray below the surface. */
float3 specular_reflect(const Surface* s, float3 d) {
    float3 r = reflect_dir(d, s->ns);
    if (dot(r, s->ng) <= 0.0f) r = reflect_dir(d, s->ng);
    return r;
}

/* Relative index of refraction across this surface for a ray arriving on s->front's side. */
float dielectric_eta(SCENE_PARAMS, const Surface* s) {
    float ior = materials[s->material].ior;
    return s->front ? ior : 1.0f / ior;
}

/* One random event at a smooth dielectric for a path arriving along *dir: reflection with
 * probability F, else refraction tinted by `base` (the Fresnel weights cancel the
 * probabilities). Updates *dir, *org and *weight; false when the refracted ray would leave on
 * the wrong side of the geometric surface (a shading-normal artefact): the path ends. */
bool sample_dielectric(SCENE_PARAMS, const Surface* sf, float u, float3 base, float3* dir, float3* org,
                       float3* weight) {
    float eta = dielectric_eta(SCENE_ARGS, sf);
    float F = fresnel_dielectric(-dot(*dir, sf->ns), eta);
    if (u < F) {
        *dir = specular_reflect(sf, *dir);
        *org = offset_origin(SCENE_ARGS, sf->p, sf->ng);
        return true;
    }
    *dir = refract_dir(*dir, sf->ns, eta);
    if (dot(*dir, sf->ng) >= 0.0f) return false;
    *weight *= base;
    *org = offset_origin(SCENE_ARGS, sf->p, -sf->ng);
    return true;
}

float material_alpha(__global const Material* m) { return fmax(m->roughness * m->roughness, 1e-4f); }

/* The kind of the metal part of a metallic surface: a mirror when perfectly smooth. */
uint metal_kind(__global const Material* m) {
    if (!HAS_GLOSSY) return MATERIAL_MIRROR;
    if (!HAS_MIRROR) return MATERIAL_GLOSSY;
    return m->roughness > 0.0f ? MATERIAL_GLOSSY : MATERIAL_MIRROR;
}

/* The material kind at this surface once METAL_MIX has been resolved with u (the metal with
 * probability metallic, else diffuse). */
uint resolve_kind(SCENE_PARAMS, const Surface* s, float u) {
    __global const Material* m = &materials[s->material];
    if (!HAS_NON_DIFFUSE) return MATERIAL_DIFFUSE;
    if (HAS_METAL_MIX && m->kind == MATERIAL_METAL_MIX) return u < m->metallic ? metal_kind(m) : MATERIAL_DIFFUSE;
    return m->kind;
}

#endif
