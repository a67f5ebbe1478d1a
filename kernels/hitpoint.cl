/* hitpoint.cl: writing a hit point, and the BRDF the gather and direct lighting evaluate there:
 * Lambertian (alpha 0) or the GGX conductor. */
#ifndef CLPPM_HITPOINT_CL
#define CLPPM_HITPOINT_CL

#include "shared_types.h"
#include "sampling.cl"
#include "ggx.cl"

void store_hitpoint(__global HitPoint* hp, uint pixel, float3 p, float3 ns, float3 ng, float3 wo, float3 weight,
                    float3 color, float alpha, float footprint) {
    hp->pos[0] = p.x; hp->pos[1] = p.y; hp->pos[2] = p.z;
    hp->weight[0] = weight.x; hp->weight[1] = weight.y; hp->weight[2] = weight.z;
    hp->color[0] = color.x; hp->color[1] = color.y; hp->color[2] = color.z;
    hp->alpha = alpha;
    hp->footprint = footprint;
    hp->normal_oct = oct_encode(ns);
    hp->ng_oct = oct_encode(ng);
    hp->wo_oct = oct_encode(wo);
    hp->pad0 = 0;
    hp->pixel = pixel;
}

/* f(wo, wi) at the hit point; zero for light from below the surface. */
float3 hitpoint_brdf(__global const HitPoint* hp, float3 n, float3 wi) {
    float3 wo = hp->alpha == 0.0f ? n : oct_decode(hp->wo_oct); /* Lambertian ignores wo */
    return nonspecular_brdf(n, wo, wi, load3g(hp->color), hp->alpha);
}

#endif
