/* direct_light.cl: explicit direct lighting at the hit points, one light sample per hit point per
 * pass, averaged over passes (used with --direct sample; photons then carry indirect light and
 * caustics only). A shadow ray through the world's medium takes its transmittance; at a volume hit
 * point the light sample is scattered by the phase function, through the hit point's own medium,
 * and weighed against a sample of the phase function (volume_direct_light). */
#ifndef CLPPM_DIRECT_LIGHT_CL
#define CLPPM_DIRECT_LIGHT_CL

#include "portability.h"
#include "rng.cl"
#include "lights.cl"
#include "hitpoint.cl"
#include "medium_light.cl"
#include "next_event.cl"

/* The direct light scattered towards the eye at x, a volume hit point hp's position or a point of
 * beam hp (kernels/beam.cl), through hp's medium (sigma_t in color, g in f90, wo_oct towards the
 * eye), before its weight: one light sample and one direction sampled from the phase function,
 * whose ray finds what emits, weighted by the power heuristic against each other (Veach 1997, Sec.
 * 9.2), as the path tracer's medium_next_event is. Light sampling alone had a heavy tail near an
 * emitting wall (1/d^2 to the wall's points next to x): a beam ends on the wall it looks at. A point
 * inside a mesh finds its lights through the surface only (either ray stops there). */
float3 volume_direct_light(SCENE_PARAMS, __global const HitPoint* hp, float3 x, Rng* rng) {
    const float3 wo = oct_decode(hp->wo_oct), sigma = load3g(hp->color);
    const float g = hp->f90;
    float3 L = (float3)(0.0f);
    LightSample s;
    if (sample_light_full(SCENE_ARGS, x, rng, &s)) {
        const float ph = hg_phase(-dot(s.wi, wo), g);
        if (ph > 0.0f && !trace_occluded(SCENE_ARGS, x, s.wi, s.dist)) {
            const float mis = s.delta ? 1.0f : power_heuristic(s.pdf_w, ph);
            L += s.contrib * light_sample_transmittance(SCENE_ARGS, sigma, &s) * (ph * mis);
        }
    }
    /* the phase function's sample: p / pdf = 1 */
    float pdf;
    const float u0 = rng_float(rng), u1 = rng_float(rng);
    const float3 w = hg_sample(-wo, g, (float2)(u0, u1), &pdf);
    Hit hit;
    if (trace_closest(SCENE_ARGS, x, w, INFINITY, &hit)) {
        Surface sf = make_surface(SCENE_ARGS, w, &hit);
        const float3 le = surface_emission(SCENE_ARGS, &sf, w);
        if (max3(le) > 0.0f) L += le * medium_transmittance(sigma, sf.t) * emission_mis(SCENE_ARGS, &sf, w, pdf);
    } else if (HAS_ENV_LIGHT) {
        L += escaped_radiance(SCENE_ARGS, w, false, false, pdf) * medium_transmittance(sigma, INFINITY);
    }
    return L;
}

__kernel SCALAR_WORK_ITEMS void direct_light(SCENE_PARAMS, ulong seed, ulong pass, __global const HitPoint* hitpoints,
                                             __global HitStats* stats, uint num_hitpoints) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (hp->pixel == HITPOINT_NONE) return;
    Rng rng = rng_make(seed, pass, i, RNG_DIRECT);
    float3 x = load3g(hp->pos);
    float3 L;
    if (hitpoint_in_volume(hp)) {
        L = load3g(hp->weight) * volume_direct_light(SCENE_ARGS, hp, x, &rng);
    } else {
        LightSample s;
        if (!sample_light_full(SCENE_ARGS, x, &rng, &s)) return;
        float3 n = oct_decode(hp->normal_oct), ng = oct_decode(hp->ng_oct);
        HitBrdf brdf = hitpoint_brdf_make(hp, n);
        float cos_x = dot(s.wi, n);
        /* From below only through diffuse transmission (bsdf_connects). */
        if (!bsdf_connects(&brdf.b, s.wi, brdf.lobes)) return;
        float3 org = offset_origin(SCENE_ARGS, x, cos_x < 0.0f ? -ng : ng);
        if (trace_occluded(SCENE_ARGS, org, s.wi, s.dist)) return;
        L = load3g(hp->weight) * hitpoint_brdf(&brdf, s.wi) * s.contrib * fabs(cos_x);
        /* through the medium of the side the sample leaves on (kernels/medium.cl) */
        if (HAS_MEDIUM) {
            const float3 sigma = volume_sigma_t(SCENE_ARGS, cos_x < 0.0f ? hp->volume_behind : hp->volume);
            if (max3(sigma) > 0.0f) L *= light_sample_transmittance(SCENE_ARGS, sigma, &s);
        }
    }
    stats[i].direct[0] += L.x;
    stats[i].direct[1] += L.y;
    stats[i].direct[2] += L.z;
}

#endif
