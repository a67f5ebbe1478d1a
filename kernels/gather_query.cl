/* gather_query.cl: a hit point as both gathers over the photon grid see it (gather.cl's flux,
 * error_estimate.cl's Laplacian), and what an accepted photon brings it: f(x, w_p, w_o) Phi_p
 * (Hachisuka et al. 2008, Eq. 9), at this pass's wavelength, as if the whole disc had been
 * covered (disc_coverage.cl). The path throughput is applied later. */
#ifndef CLPPM_GATHER_QUERY_CL
#define CLPPM_GATHER_QUERY_CL

#include "gather_common.cl"
#include "dispersion.cl"
#include "medium.cl"

/* The parameters of both gather kernels (gather.cl, error_estimate.cl's error_gather) in the order
 * PhotonMap::enqueue_gather sets them, one call for either: the grid, the photons sorted by cell and
 * each cell's first, the hit points and their statistics, PPPM's radius (global_r2 > 0), the
 * volume hit points' radius (volume_r2 > 0: the same for all of a pass, SppmIntegrator), whether
 * to add to `out` (a pass in several photon batches), the pass's wavelength and disc coverage. */
#define GATHER_KERNEL_PARAMS(out_type)                                                                                 \
    __constant GridInfo *g, __global const Photon *sorted, __global const uint *starts,                                \
        __global const HitPoint *hitpoints, __global const HitStats *stats, uint num_hitpoints, float global_r2,       \
        float volume_r2, uint accumulate, __global out_type *out, ulong seed, ulong pass,                              \
        __global const float2 *coverage

/* c added to three fixed-point sums (FLUX_FIXED_SCALE): exact, in any order. */
void add_fixed_point(float3 c, long* a0, long* a1, long* a2) {
    *a0 += convert_long_rte((double)c.x * FLUX_FIXED_SCALE);
    *a1 += convert_long_rte((double)c.y * FLUX_FIXED_SCALE);
    *a2 += convert_long_rte((double)c.z * FLUX_FIXED_SCALE);
}

/* Hit point i's sums of a pass into out[i]; a pass traced in several photon batches adds them up
 * (accumulate): integer sums, so the result is the same as for one batch. */
void store_pass_flux(__global PassFlux* out, uint i, long a0, long a1, long a2, uint m, uint accumulate) {
    if (accumulate) {
        a0 += out[i].flux[0];
        a1 += out[i].flux[1];
        a2 += out[i].flux[2];
        m += out[i].m;
    }
    out[i].flux[0] = a0;
    out[i].flux[1] = a1;
    out[i].flux[2] = a2;
    out[i].m = m;
}

typedef struct {
    float3 x, n;       /* position and normal */
    HitBrdf brdf;      /* the lobes the hit point keeps */
    float r2;          /* this pass's squared radius */
    PassWavelength pw; /* this pass's wavelength (KHR_materials_dispersion) */
    bool dispersed;    /* the hit point's path went through dispersive glass */
    float inv_cover;   /* 1 / the disc's covered fraction */
} GatherQuery;

/* Hit point i of a pass: r2 its own R(x)^2 ((S)PPM), or PPPM's one radius for all (global_r2 > 0). */
GatherQuery gather_query(__global const HitPoint* hp, __global const HitStats* stats, uint i, float global_r2,
                         ulong seed, ulong pass, __global const float2* coverage) {
    GatherQuery q;
    q.x = load3g(hp->pos);
    q.n = oct_decode(hp->normal_oct);
    q.brdf = hitpoint_brdf_make(hp, q.n);
    q.r2 = global_r2 > 0.0f ? global_r2 : (float)stats[i].r2;
    q.pw = pass_wavelength(seed, pass);
    q.dispersed = hitpoint_dispersed(hp);
    q.inv_cover = 1.0f / coverage[i].x;
    return q;
}

/* f(x, w_p, w_o) Phi_p of photon ph, accepted from direction wi. */
float3 gather_photon(const GatherQuery* q, __global const Photon* ph, float3 wi) {
    float3 f = hitpoint_brdf(&q->brdf, wi);
    float3 phi = load3_dispersed(ph->flux) * q->inv_cover;
    if (HAS_DISPERSION) phi *= merge_dispersion(q->dispersed, is_dispersed(ph->flux[0]), &q->pw);
    return f * phi;
}

/* Which medium volume photon ph was stored in, and the medium of volume hit point or beam hp
 * (kernels/medium.cl Medium.id). */
uint photon_medium(__global const Photon* ph) { return ph->normal_oct; }
uint hitpoint_medium(__global const HitPoint* hp) { return hp->t_oct; }

/* Whether ph was stored in a medium (shared_types.h PHOTON_VOLUME_FLAG). */
bool photon_in_volume(__global const Photon* ph) {
    return HAS_MEDIUM && (as_uint(ph->flux[1]) & PHOTON_VOLUME_FLAG) != 0u;
}

/* The grid loop of a gather for query q: `...` runs per accepted photon with ph, d2 and wi in scope.
 * Surfaces take no photon stored in a medium. */
#define GATHER_QUERY_FOR_EACH_PHOTON(g_, sorted_, starts_, q_, ...)                                                    \
    GATHER_FOR_EACH_PHOTON(g_, sorted_, starts_, (q_).x, (q_).n, (q_).brdf.both_sides, (q_).r2, {                      \
        if (photon_in_volume(ph)) continue;                                                                            \
        __VA_ARGS__                                                                                                    \
    })

/* A volume hit point as the gather sees it: the in-scattered radiance at x towards wo is
 * estimated from the photons stored in media within the sphere of squared radius r2,
 *   L_s(x, wo) ~ sum_p p(-wi_p . wo) Phi_p / (sigma_t V),  V = 4/3 pi r^3
 * (Jensen and Christensen 1998, Eq. 10, with the photons' flux times sigma_t T / pdf of their
 * free flights: Photon); the hit point's weight brings sigma_s T / pdf of the eye path's. The
 * gather sums p Phi_p / sigma_t; the volume is the film's to divide by (SPPM's and PPPM's one
 * radius a pass: SppmIntegrator::volume_update; PPM's own per hit point: radiance_estimate.cl). */
typedef struct {
    float3 x, wo, inv_sigma_t;
    float g, r2;
    uint medium; /* the photons of this medium alone */
    PassWavelength pw;
    bool dispersed;
} VolumeQuery;

/* Volume hit point i of a pass: volume_r2 the pass's radius for all (SPPM, PPPM), or 0 for its own
 * R(x)^2 (PPM's fixed volume hit points, ppm_update.cl). */
VolumeQuery volume_query(__global const HitPoint* hp, __global const HitStats* stats, uint i, float volume_r2,
                         ulong seed, ulong pass) {
    VolumeQuery q;
    q.x = load3g(hp->pos);
    q.wo = oct_decode(hp->wo_oct);
    const float3 s = load3g(hp->color);
    q.inv_sigma_t =
        (float3)(s.x > 0.0f ? 1.0f / s.x : 0.0f, s.y > 0.0f ? 1.0f / s.y : 0.0f, s.z > 0.0f ? 1.0f / s.z : 0.0f);
    q.g = hp->f90;
    q.medium = hitpoint_medium(hp);
    q.r2 = volume_r2 > 0.0f ? volume_r2 : (float)stats[i].r2;
    q.pw = pass_wavelength(seed, pass);
    q.dispersed = hitpoint_dispersed(hp);
    return q;
}

/* Phi_p of the volume photon ph as a query of a path through dispersive glass or not (dispersed)
 * sees it at the pass's wavelength pw. */
float3 volume_photon_flux(__global const Photon* ph, bool dispersed, const PassWavelength* pw) {
    float3 phi =
        (float3)(without_dispersed(ph->flux[0]), as_float(as_uint(ph->flux[1]) & ~PHOTON_VOLUME_FLAG), ph->flux[2]);
    if (HAS_DISPERSION) phi *= merge_dispersion(dispersed, is_dispersed(ph->flux[0]), pw);
    return phi;
}

/* p(-wi . wo) Phi_p / sigma_t of the volume photon ph. */
float3 gather_volume_photon(const VolumeQuery* q, __global const Photon* ph) {
    const float3 wi = oct_decode(ph->wi_oct);
    return volume_photon_flux(ph, q->dispersed, &q->pw) * q->inv_sigma_t * hg_phase(-dot(wi, q->wo), q->g);
}

#endif
