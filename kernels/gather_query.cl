/* gather_query.cl: a hit point as both gathers over the photon grid see it (gather.cl's flux,
 * error_estimate.cl's Laplacian), and what an accepted photon brings it: f(x, w_p, w_o) Phi_p
 * (Hachisuka et al. 2008, Eq. 9), at this pass's wavelength, as if the whole disc had been
 * covered (disc_coverage.cl). The path throughput is applied later. */
#ifndef CLPPM_GATHER_QUERY_CL
#define CLPPM_GATHER_QUERY_CL

#include "gather_common.cl"
#include "dispersion.cl"

/* The parameters of both gather kernels (gather.cl, error_estimate.cl's error_gather) in the order
 * PhotonMap::enqueue_gather sets them, one call for either: the grid, the photons sorted by cell and
 * each cell's first, the hit points and their statistics, PPPM's radius (global_r2 > 0), whether
 * to add to `out` (a pass in several photon batches), the pass's wavelength and disc coverage. */
#define GATHER_KERNEL_PARAMS(out_type)                                                                                 \
    __constant GridInfo *g, __global const Photon *sorted, __global const uint *starts,                                \
        __global const HitPoint *hitpoints, __global const HitStats *stats, uint num_hitpoints, float global_r2,       \
        uint accumulate, __global out_type *out, ulong seed, ulong pass, __global const float2 *coverage

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

/* The grid loop of a gather for query q: `...` runs per accepted photon with ph, d2 and wi in scope. */
#define GATHER_QUERY_FOR_EACH_PHOTON(g_, sorted_, starts_, q_, ...)                                                    \
    GATHER_FOR_EACH_PHOTON(g_, sorted_, starts_, (q_).x, (q_).n, (q_).brdf.both_sides, (q_).r2, __VA_ARGS__)

#endif
