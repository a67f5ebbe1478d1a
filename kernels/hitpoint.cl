/* hitpoint.cl: writing a hit point, and the BSDF the gather and direct lighting evaluate there:
 * the lobes bsdf_gathered_lobes keeps of the material the eye path met (kernels/bsdf.cl). */
#ifndef CLPPM_HITPOINT_CL
#define CLPPM_HITPOINT_CL

#include "shared_types.h"
#include "sampling.cl"
#include "bsdf.cl"

void store_hitpoint(__global HitPoint* hp, uint pixel, float3 p, float3 wo, float3 weight, const Bsdf* b,
                    float footprint, uint volume, uint volume_behind) {
    hp->pos[0] = p.x;
    hp->pos[1] = p.y;
    hp->pos[2] = p.z;
    hp->weight[0] = weight.x;
    hp->weight[1] = weight.y;
    hp->weight[2] = weight.z;
    hp->color[0] = b->base.x;
    hp->color[1] = b->base.y;
    hp->color[2] = b->base.z;
    hp->alpha = b->alpha;
    hp->f0[0] = b->f0.x;
    hp->f0[1] = b->f0.y;
    hp->f0[2] = b->f0.z;
    hp->f90 = b->f90;
    hp->dielectric = b->dielectric;
    hp->metal = b->metal;
    hp->footprint = footprint;
    hp->normal_oct = oct_encode(b->ns);
    hp->ng_oct = oct_encode(b->ng);
    hp->wo_oct = oct_encode(wo);
    hp->nl_oct = oct_encode(b->nl);
    hp->coat = HAS_CLEARCOAT ? b->coat : 0.0f;
    hp->coat_alpha = b->coat_alpha;
    hp->nc_oct = oct_encode(b->nc);
    hp->sheen[0] = HAS_SHEEN ? b->sheen.x : 0.0f;
    hp->sheen[1] = HAS_SHEEN ? b->sheen.y : 0.0f;
    hp->sheen[2] = HAS_SHEEN ? b->sheen.z : 0.0f;
    hp->sheen_r = b->sheen_r;
    hp->irid = HAS_IRIDESCENCE ? b->irid : 0.0f;
    hp->irid_ior = b->irid_ior;
    hp->irid_d = b->irid_d;
    hp->t_oct = HAS_ANISOTROPY ? oct_encode(b->ta) : 0u;
    hp->alpha_t = b->alpha_t;
    hp->translucent[0] = HAS_DIFFUSE_TRANSMISSION ? b->translucent.x : 0.0f;
    hp->translucent[1] = HAS_DIFFUSE_TRANSMISSION ? b->translucent.y : 0.0f;
    hp->translucent[2] = HAS_DIFFUSE_TRANSMISSION ? b->translucent.z : 0.0f;
    hp->dt = HAS_DIFFUSE_TRANSMISSION ? b->dt : 0.0f;
    hp->volume = volume;
    hp->volume_behind = volume_behind;
    hp->pixel = pixel;
}

/* Whether hp lies in a medium, a volume hit point or a beam (shared_types.h): none has surface
 * statistics. Never in a program for scenes without media. */
bool hitpoint_in_volume(__global const HitPoint* hp) { return HAS_MEDIUM && hp->alpha < 0.0f; }

/* Whether hp is a beam (shared_types.h), which kernels/beam.cl gathers for. */
bool hitpoint_is_beam(__global const HitPoint* hp) { return HAS_MEDIUM && hp->alpha == HITPOINT_BEAM_ALPHA; }

/* A volume hit point at p, seen from wo, in medium `medium` (Medium.id, in t_oct) of extinction
 * sigma_t and phase g; weight is the eye path's throughput times sigma_s T / pdf of its free
 * flight. Every field written. */
void store_volume_hitpoint(__global HitPoint* hp, uint pixel, float3 p, float3 wo, float3 weight, float3 sigma_t,
                           float g, uint medium, float footprint) {
    HitPoint v;
    v.pos[0] = p.x;
    v.pos[1] = p.y;
    v.pos[2] = p.z;
    v.pixel = pixel;
    v.weight[0] = weight.x;
    v.weight[1] = weight.y;
    v.weight[2] = weight.z;
    v.footprint = footprint;
    v.color[0] = sigma_t.x;
    v.color[1] = sigma_t.y;
    v.color[2] = sigma_t.z;
    v.alpha = HITPOINT_VOLUME_ALPHA;
    v.f0[0] = v.f0[1] = v.f0[2] = 0.0f;
    v.f90 = g;
    v.dielectric = v.metal = 0.0f;
    v.wo_oct = oct_encode(wo);
    v.normal_oct = v.ng_oct = v.nl_oct = v.nc_oct = v.wo_oct;
    v.coat = v.coat_alpha = 0.0f;
    v.sheen[0] = v.sheen[1] = v.sheen[2] = v.sheen_r = 0.0f;
    v.irid = v.irid_ior = v.irid_d = 0.0f;
    v.t_oct = medium;
    v.alpha_t = 0.0f;
    v.translucent[0] = v.translucent[1] = v.translucent[2] = v.dt = 0.0f;
    v.volume = v.volume_behind = medium;
    *hp = v;
}

/* A beam (shared_types.h): the segment o + t d, t in [0, t_max], of a camera ray of throughput
 * weight at o through the medium `medium` (sigma_t, albedo, g). Every field written. */
void store_beam(__global HitPoint* hp, uint pixel, float3 o, float3 d, float t_max, float3 weight, float3 sigma_t,
                float3 albedo, float g, uint medium, float footprint) {
    store_volume_hitpoint(hp, pixel, o, -d, weight, sigma_t, g, medium, footprint);
    hp->alpha = HITPOINT_BEAM_ALPHA;
    hp->f0[0] = d.x;
    hp->f0[1] = d.y;
    hp->f0[2] = d.z;
    hp->dielectric = t_max;
    hp->sheen[0] = albedo.x;
    hp->sheen[1] = albedo.y;
    hp->sheen[2] = albedo.z;
}

/* The material at the hit point, with shading normal n (decoded once by the caller). */
Bsdf hitpoint_bsdf(__global const HitPoint* hp, float3 n) {
    Bsdf b;
    b.ns = n;
    b.ng = oct_decode(hp->ng_oct);
    b.nl = HAS_NORMAL_MAPS ? oct_decode(hp->nl_oct) : n;
    b.base = load3g(hp->color);
    b.alpha = hp->alpha;
    b.f0 = load3g(hp->f0);
    b.f90 = hp->f90;
    b.dielectric = hp->dielectric;
    b.metal = hp->metal;
    b.glass = 0.0f;
    b.eta = 1.0f;
    b.thin = false;
    b.radiance = true; /* the eye's side */
    b.front = true;
    b.sigma = (float3)(0.0f);
    b.coat = HAS_CLEARCOAT ? hp->coat : 0.0f;
    b.coat_alpha = hp->coat_alpha;
    b.nc = HAS_CLEARCOAT ? oct_decode(hp->nc_oct) : n;
    b.sheen = HAS_SHEEN ? load3g(hp->sheen) : (float3)(0.0f);
    b.sheen_r = hp->sheen_r;
    b.irid = HAS_IRIDESCENCE ? hp->irid : 0.0f;
    b.irid_ior = hp->irid_ior;
    b.irid_d = hp->irid_d;
    b.alpha_t = HAS_ANISOTROPY ? hp->alpha_t : b.alpha;
    b.ta = HAS_ANISOTROPY && b.alpha_t != b.alpha ? oct_decode(hp->t_oct) : n;
    b.dt = HAS_DIFFUSE_TRANSMISSION ? hp->dt : 0.0f;
    b.translucent = HAS_DIFFUSE_TRANSMISSION ? load3g(hp->translucent) : (float3)(0.0f);
    return b;
}

/* What the gather evaluates per photon at one hit point, prepared once: the BSDF, the direction
 * to the eye, the lobes kept, and the constant f of a plain Lambertian surface (the common case,
 * which then costs one comparison per photon). */
typedef struct {
    Bsdf b;
    float3 wo;
    uint lobes;
    bool lambert;
    bool both_sides; /* transmits diffusely: photons from behind count too (gather_faces) */
    float3 f_lambert;
} HitBrdf;

HitBrdf hitpoint_brdf_make(__global const HitPoint* hp, float3 n) {
    HitBrdf h;
    h.b = hitpoint_bsdf(hp, n);
    h.wo = HAS_NON_DIFFUSE ? oct_decode(hp->wo_oct) : n; /* Lambertian ignores wo */
    h.lobes = bsdf_gathered(&h.b);
    h.lambert = bsdf_plain_lambert(&h.b);
    h.both_sides = has_translucent(&h.b);
    h.f_lambert = h.b.base * (h.b.dielectric * INV_PI_F);
    return h;
}

/* f(wo, wi) at the hit point over the lobes it keeps; zero for light from below the surface unless
 * it transmits diffusely. */
float3 hitpoint_brdf(const HitBrdf* h, float3 wi) {
    if (h->lambert) return dot(h->b.ns, wi) > 0.0f && bsdf_smooth_side(&h->b, wi) ? h->f_lambert : (float3)(0.0f);
    return bsdf_eval(&h->b, h->wo, wi, h->lobes);
}

#endif
