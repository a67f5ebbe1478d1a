/* eye_pass.cl: the first pass of progressive photon mapping (Hachisuka et al. 2008, Sec. 4.1).
 * Each pixel sample follows specular chains from the camera to the first non-specular surfaces
 * (diffuse, or glossy at least GLOSSY_HITPOINT_ALPHA rough) and stores a hit point there.
 * Smoother glossy surfaces are importance-sampled through (VNDF) like mirrors.
 * Where a dielectric or a partly metallic surface splits the path, both branches are followed
 * with their Fresnel / metallic weights while slots remain (EYE_SLOTS per sample), so the stored
 * set of hit points carries no sampling noise from those choices; beyond that one branch is
 * chosen at random with the same expected value. Emission met on the way is added to the
 * sample's radiance directly.
 * Stochastic PPM and PPPM build this with EYE_SLOTS 1 and run it every pass with a new `pass`:
 * one visible point per pixel, every choice sampled, new jitter and lens position each pass. */
#include "rng.cl"
#include "camera.cl"
#include "bsdf.cl"
#include "hitpoint.cl"

#ifndef EYE_SLOTS
#define EYE_SLOTS PPM_EYE_SLOTS /* the host passes -DEYE_SLOTS=PPM_EYE_SLOTS or SPPM_EYE_SLOTS */
#endif
/* A split is only worth a slot when both branches carry real weight. */
#define SPLIT_MIN_WEIGHT 0.02f

typedef struct {
    float3 org, dir, weight;
    float path_length;
    uint depth;
} EyeRay;

/* One way an eye path can go on from a surface: a new ray, or a hit point here. */
typedef struct {
    float3 weight;
    float3 dir;   /* ray branches */
    bool below;   /* the ray leaves through the surface (refraction) */
    bool hitpoint;
    float3 color; /* hit point branches: albedo or F0 */
    float alpha;
} Branch;

Branch no_branch(void) {
    Branch b;
    b.weight = (float3)(0.0f);
    b.dir = (float3)(0.0f);
    b.below = false;
    b.hitpoint = false;
    b.color = (float3)(0.0f);
    b.alpha = 0.0f;
    return b;
}

Branch hitpoint_branch(float3 weight, float3 color, float alpha) {
    Branch b = no_branch();
    b.weight = weight;
    b.hitpoint = true;
    b.color = color;
    b.alpha = alpha;
    return b;
}

Branch ray_branch(float3 weight, float3 dir, bool below) {
    Branch b = no_branch();
    b.weight = weight;
    b.dir = dir;
    b.below = below;
    return b;
}

/* The metal part of a surface: mirror, glossy hit point, or a sampled glossy ray. */
Branch metal_branch(SCENE_PARAMS, const Surface* sf, float3 in_dir, float3 weight, float3 base, Rng* rng) {
    __global const Material* m = &materials[sf->material];
    if (!HAS_GLOSSY || metal_kind(m) == MATERIAL_MIRROR) return ray_branch(weight * base, specular_reflect(sf, in_dir), false);
    float alpha = material_alpha(m);
    if (alpha >= GLOSSY_HITPOINT_ALPHA) return hitpoint_branch(weight, base, alpha);
    float3 wi;
    float3 w = ggx_sample(sf->ns, -in_dir, base, alpha, rng_float(rng), rng_float(rng), &wi);
    if (dot(wi, sf->ng) <= 0.0f) w = (float3)(0.0f);
    return ray_branch(weight * w, wi, false);
}

/* The (at most two) continuations of an eye path at a surface. */
void surface_branches(SCENE_PARAMS, const Surface* sf, float3 in_dir, float3 weight, Rng* rng, Branch* a, Branch* b) {
    __global const Material* m = &materials[sf->material];
    float3 base = surface_base_color(SCENE_ARGS, sf);
    *a = no_branch();
    *b = no_branch();
    if (!HAS_NON_DIFFUSE || m->kind == MATERIAL_DIFFUSE) {
        *a = hitpoint_branch(weight, base, 0.0f);
    } else if ((HAS_MIRROR || HAS_GLOSSY) && (m->kind == MATERIAL_MIRROR || m->kind == MATERIAL_GLOSSY)) {
        *a = metal_branch(SCENE_ARGS, sf, in_dir, weight, base, rng);
    } else if (HAS_METAL_MIX && m->kind == MATERIAL_METAL_MIX) {
        *a = metal_branch(SCENE_ARGS, sf, in_dir, weight * m->metallic, base, rng);
        *b = hitpoint_branch(weight * (1.0f - m->metallic), base, 0.0f);
    } else if (HAS_DIELECTRIC) {
        float eta = dielectric_eta(SCENE_ARGS, sf);
        float F = fresnel_dielectric(-dot(in_dir, sf->ns), eta);
        *a = ray_branch(weight * F, specular_reflect(sf, in_dir), false);
        if (F < 1.0f) {
            float3 t = refract_dir(in_dir, sf->ns, eta);
            if (dot(t, sf->ng) < 0.0f) *b = ray_branch(weight * base * (1.0f - F), t, true);
        }
    }
}

__kernel void eye_pass(SCENE_PARAMS, __constant Camera* cam, ulong seed, ulong pass, uint first_sample, uint num_samples,
                       uint spp, __global HitPoint* hitpoints, __global float4* sample_emission) {
    uint i = get_global_id(0);
    if (i >= num_samples) return;
    uint gsample = first_sample + i;
    uint pixel = gsample / spp, s = gsample % spp;
    Rng rng = rng_make(seed, pass, gsample, RNG_EYE);

    float2 off = pixel_sample_offset(s, spp, EYE_SLOTS == 1, &rng);
    float2 lens = (float2)(rng_float(&rng), rng_float(&rng));
    float px = (float)(pixel % cam->width) + off.x, py = (float)(pixel / cam->width) + off.y;
    /* Pixel footprint per unit distance: the angle one pixel subtends (initial radius heuristic). */
    float pixel_angle = 2.0f * length(load3c(cam->up)) / (float)cam->height;

    EyeRay stack[EYE_SLOTS];
    uint top = 0, stored = 0;
    camera_ray(cam, px, py, lens, &stack[0].org, &stack[0].dir);
    stack[0].weight = (float3)(1.0f);
    stack[0].path_length = 0.0f;
    stack[0].depth = 0;
    top = 1;
    float3 emitted = (float3)(0.0f);
    __global HitPoint* out = &hitpoints[(size_t)i * EYE_SLOTS];
    for (uint k = 0; k < EYE_SLOTS; ++k) out[k].pixel = HITPOINT_NONE;

    while (top > 0) {
        EyeRay r = stack[--top];
        Hit hit;
        if (!trace_closest(SCENE_ARGS, r.org, r.dir, INFINITY, &hit)) continue;
        Surface sf = make_surface(SCENE_ARGS, r.dir, &hit);
        emitted += r.weight * surface_emission(SCENE_ARGS, &sf);
        if (r.depth + 1 >= info->max_bounces) continue;
        float plen = r.path_length + sf.t;

        Branch br[2];
        surface_branches(SCENE_ARGS, &sf, r.dir, r.weight, &rng, &br[0], &br[1]);
        float m0 = max3(br[0].weight), m1 = max3(br[1].weight);
        bool take0 = m0 > 0.0f, take1 = m1 > 0.0f;
        if (take0 && take1) {
            /* Split only when a slot is free for the extra branch and both matter; otherwise keep
             * one, chosen in proportion to weight and reweighted (expected value unchanged). */
            bool room = top + stored + 2 <= EYE_SLOTS;
            if (!room || fmin(m0, m1) < SPLIT_MIN_WEIGHT * max3(r.weight)) {
                float p0 = m0 / (m0 + m1);
                if (rng_float(&rng) < p0) {
                    take1 = false;
                    br[0].weight /= p0;
                } else {
                    take0 = false;
                    br[1].weight /= (1.0f - p0);
                }
            }
        }
        for (int k = 0; k < 2; ++k) {
            if (!(k == 0 ? take0 : take1)) continue;
            Branch b = br[k];
            if (b.hitpoint) {
                store_hitpoint(&out[stored++], pixel, sf.p, sf.ns, sf.ng, -r.dir, b.weight, b.color, b.alpha,
                               plen * pixel_angle);
            } else {
                EyeRay nr = {offset_origin(SCENE_ARGS, sf.p, b.below ? -sf.ng : sf.ng), b.dir, b.weight, plen,
                             r.depth + 1};
                stack[top++] = nr;
            }
        }
    }
    sample_emission[i] = (float4)(emitted, 0.0f);
}
