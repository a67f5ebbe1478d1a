/* direct_light.cl: explicit direct lighting at the hit points, one light sample per hit point per
 * pass, averaged over passes (used with --direct sample; photons then carry indirect light and
 * caustics only). A shadow ray through the world's medium takes its transmittance; at a volume hit
 * point the light sample is scattered by the phase function, through the hit point's own medium. */
#include "portability.h"
#include "rng.cl"
#include "lights.cl"
#include "hitpoint.cl"
#include "medium_light.cl"

/* The light sample s scattered towards the eye at the volume hit point hp (at x), before its
 * weight: the phase function, the shadow ray and the transmittance of hp's medium along it. A
 * volume hit point inside a mesh finds its lights through the surface only (the shadow ray stops there). */
float3 volume_direct_light(SCENE_PARAMS, __global const HitPoint* hp, float3 x, const LightSample* s) {
    const float ph = hg_phase(-dot(s->wi, oct_decode(hp->wo_oct)), hp->f90);
    if (!(ph > 0.0f) || trace_occluded(SCENE_ARGS, x, s->wi, s->dist)) return (float3)(0.0f);
    return s->contrib * light_sample_transmittance(SCENE_ARGS, load3g(hp->color), s) * ph;
}

__kernel SCALAR_WORK_ITEMS void direct_light(SCENE_PARAMS, ulong seed, ulong pass, __global const HitPoint* hitpoints,
                                             __global HitStats* stats, uint num_hitpoints) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (hp->pixel == HITPOINT_NONE) return;
    Rng rng = rng_make(seed, pass, i, RNG_DIRECT);
    float3 x = load3g(hp->pos);
    LightSample s;
    if (!sample_light_full(SCENE_ARGS, x, &rng, &s)) return;
    float3 L;
    if (hitpoint_in_volume(hp)) {
        L = load3g(hp->weight) * volume_direct_light(SCENE_ARGS, hp, x, &s);
    } else {
        float3 n = oct_decode(hp->normal_oct), ng = oct_decode(hp->ng_oct);
        HitBrdf brdf = hitpoint_brdf_make(hp, n);
        float cos_x = dot(s.wi, n);
        /* From below only through diffuse transmission (bsdf_connects). */
        if (!bsdf_connects(&brdf.b, s.wi, brdf.lobes)) return;
        float3 org = offset_origin(SCENE_ARGS, x, cos_x < 0.0f ? -ng : ng);
        if (trace_occluded(SCENE_ARGS, org, s.wi, s.dist)) return;
        L = load3g(hp->weight) * hitpoint_brdf(&brdf, s.wi) * s.contrib * fabs(cos_x);
        /* hit points lie in the world's medium (a mesh's inside is reached through glass) */
        if (world_has_medium(info)) L *= light_sample_transmittance(SCENE_ARGS, world_sigma_t(info), &s);
    }
    stats[i].direct[0] += L.x;
    stats[i].direct[1] += L.y;
    stats[i].direct[2] += L.z;
}
