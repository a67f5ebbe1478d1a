/* direct_light.cl: explicit direct lighting at the hit points, one light sample per hit point per
 * pass, averaged over passes (used with --direct sample; photons then carry indirect light and
 * caustics only). */
#include "portability.h"
#include "rng.cl"
#include "lights.cl"
#include "hitpoint.cl"

__kernel SCALAR_WORK_ITEMS void direct_light(SCENE_PARAMS, ulong seed, ulong pass, __global const HitPoint* hitpoints,
                                             __global HitStats* stats, uint num_hitpoints) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (hp->pixel == HITPOINT_NONE) return;
    Rng rng = rng_make(seed, pass, i, RNG_DIRECT);
    float3 x = load3g(hp->pos), n = oct_decode(hp->normal_oct), ng = oct_decode(hp->ng_oct);
    HitBrdf brdf = hitpoint_brdf_make(hp, n);
    float3 wi, contrib;
    float dist, pdf;
    if (!sample_light(SCENE_ARGS, x, &rng, &wi, &dist, &contrib, &pdf)) return;
    float cos_x = dot(wi, n);
    /* From below only through diffuse transmission (bsdf_connects). */
    if (!bsdf_connects(&brdf.b, wi, brdf.lobes)) return;
    float3 org = offset_origin(SCENE_ARGS, x, cos_x < 0.0f ? -ng : ng);
    if (trace_occluded(SCENE_ARGS, org, wi, dist)) return;
    float3 L = load3g(hp->weight) * hitpoint_brdf(&brdf, wi) * contrib * fabs(cos_x);
    stats[i].direct[0] += L.x;
    stats[i].direct[1] += L.y;
    stats[i].direct[2] += L.z;
}
