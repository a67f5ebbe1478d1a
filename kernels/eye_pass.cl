/* eye_pass.cl: the first pass of progressive photon mapping (Hachisuka et al. 2008, Sec. 4.1).
 * Each pixel sample follows specular chains from the camera to the first non-specular surfaces
 * and stores a hit point there. Where a dielectric or a partly metallic surface splits the path,
 * both branches are followed with their Fresnel / metallic weights while slots remain
 * (EYE_SLOTS per sample), so the stored set of hit points carries no sampling noise from those
 * choices; beyond that one branch is chosen at random with the same expected value.
 * Emission met on the way is added to the sample's radiance directly.
 * Stochastic PPM and PPPM build this with EYE_SLOTS 1 and run it every pass with a new `pass`:
 * one visible point per pixel, every choice sampled, new jitter and lens position each pass. */
#include "rng.cl"
#include "camera.cl"
#include "bsdf.cl"

#ifndef EYE_SLOTS
#define EYE_SLOTS 4
#endif
/* A split is only worth a slot when both branches carry real weight. */
#define SPLIT_MIN_WEIGHT 0.02f

typedef struct {
    float3 org, dir, weight;
    float path_length;
    uint depth;
} EyeRay;

__kernel void eye_pass(SCENE_PARAMS, __constant Camera* cam, ulong seed, ulong pass, uint first_sample, uint num_samples,
                       uint spp, __global HitPoint* hitpoints, __global float4* sample_emission) {
    uint i = get_global_id(0);
    if (i >= num_samples) return;
    uint gsample = first_sample + i;
    uint pixel = gsample / spp, s = gsample % spp;
    Rng rng = rng_make(seed, pass, gsample, RNG_EYE);

    float2 off = pixel_sample_offset(s, spp, &rng);
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
        __global const Material* m = &materials[sf.material];
        float3 base = surface_base_color(SCENE_ARGS, &sf);
        float plen = r.path_length + sf.t;

        /* The weights of the two possible continuations: a (specular) and b (the other). */
        float3 wa = (float3)(0.0f), wb = (float3)(0.0f);
        float3 da = (float3)(0.0f), db = (float3)(0.0f);
        bool b_is_hitpoint = false;
        if (m->kind == MATERIAL_DIFFUSE) {
            wb = r.weight;
            b_is_hitpoint = true;
        } else if (m->kind == MATERIAL_MIRROR) {
            wa = r.weight * base;
            da = specular_reflect(&sf, r.dir);
        } else if (m->kind == MATERIAL_METAL_MIX) {
            wa = r.weight * base * m->metallic;
            da = specular_reflect(&sf, r.dir);
            wb = r.weight * (1.0f - m->metallic);
            b_is_hitpoint = true;
        } else { /* MATERIAL_DIELECTRIC */
            float eta = dielectric_eta(SCENE_ARGS, &sf);
            float F = fresnel_dielectric(-dot(r.dir, sf.ns), eta);
            wa = r.weight * F;
            da = specular_reflect(&sf, r.dir);
            if (F < 1.0f) {
                wb = r.weight * base * (1.0f - F);
                db = refract_dir(r.dir, sf.ns, eta);
                if (dot(db, sf.ng) >= 0.0f) wb = (float3)(0.0f); /* shading normal artefact */
            }
        }
        float ma = max3(wa), mb = max3(wb);
        bool take_a = ma > 0.0f, take_b = mb > 0.0f;
        if (take_a && take_b) {
            /* Split only when a slot is free for the extra branch and both matter; otherwise keep
             * one, chosen in proportion to weight and reweighted (expected value unchanged). */
            bool room = top + stored + 2 <= EYE_SLOTS;
            if (!room || fmin(ma, mb) < SPLIT_MIN_WEIGHT * max3(r.weight)) {
                float pa = ma / (ma + mb);
                if (rng_float(&rng) < pa) {
                    take_b = false;
                    wa /= pa;
                } else {
                    take_a = false;
                    wb /= (1.0f - pa);
                }
            }
        }
        if (take_b && b_is_hitpoint) {
            __global HitPoint* hp = &out[stored++];
            hp->pos[0] = sf.p.x; hp->pos[1] = sf.p.y; hp->pos[2] = sf.p.z;
            hp->normal[0] = sf.ns.x; hp->normal[1] = sf.ns.y; hp->normal[2] = sf.ns.z;
            hp->ng_oct = oct_encode(sf.ng);
            float3 f = wb * base * INV_PI_F; /* path weight times the Lambertian BRDF */
            hp->weight[0] = f.x; hp->weight[1] = f.y; hp->weight[2] = f.z;
            hp->footprint = plen * pixel_angle;
            hp->pixel = pixel;
        } else if (take_b) {
            EyeRay nb = {offset_origin(SCENE_ARGS, sf.p, -sf.ng), db, wb, plen, r.depth + 1};
            stack[top++] = nb;
        }
        if (take_a) {
            EyeRay na = {offset_origin(SCENE_ARGS, sf.p, sf.ng), da, wa, plen, r.depth + 1};
            stack[top++] = na;
        }
    }
    sample_emission[i] = (float4)(emitted, 0.0f);
}
