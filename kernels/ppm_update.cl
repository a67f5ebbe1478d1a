/* ppm_update.cl: the progressive radius and flux update (Hachisuka et al. 2008, Eqs. 7-10):
 *   N' = N + alpha M,  R'^2 = R^2 (N + alpha M) / (N + M),  tau' = (tau + tau_M) (N + alpha M) / (N + M)
 * in double precision. The gather summed f Phi over the photons; tau_M is that times the hit
 * point's path throughput. PPM's fixed volume hit points keep the same statistics in three
 * dimensions: the sphere's volume, not the disc's area, shrinks by the ratio, R'^3 = R^3 (N + alpha
 * M) / (N + M), and tau by the same ratio (the photons of the smaller sphere, at a constant density
 * within it, as Eq. 9 assumes of the disc); L = tau / (4/3 pi R^3 N_emitted) (radiance_estimate.cl). */
#include "shared_types.h"
#include "hitpoint.cl"

/* in_volume: the hit point's sphere shrinks in volume by the ratio (R^2 by its 2/3 power). */
void ppm_update_stats(__global HitStats* s, double M, double3 tau_M, double alpha, bool in_volume) {
    if (M <= 0.0) return; /* no photon: nothing changes (Eq. 7 with M = 0) */
    double N = s->n;
    double ratio = (N + alpha * M) / (N + M);
    s->n = N + alpha * M;
    s->r2 *= in_volume ? pow(ratio, 2.0 / 3.0) : ratio;
    s->tau[0] = (s->tau[0] + tau_M.x) * ratio;
    s->tau[1] = (s->tau[1] + tau_M.y) * ratio;
    s->tau[2] = (s->tau[2] + tau_M.z) * ratio;
}

/* Also reduces sum and max of R per work-group into radius_partials (for the next grid's cell
 * size; the image does not depend on it). Launched with local size PPM_UPDATE_WG. volume_stats:
 * volume hit points keep statistics of their own (PPM's fixed ones); else their estimate is not
 * progressive per hit point (SPPM and PPPM: sppm.cl volume_accumulate) and they are left alone. */
__kernel __attribute__((reqd_work_group_size(PPM_UPDATE_WG, 1, 1))) void ppm_update(
    __global const PassFlux* pass, __global const HitPoint* hitpoints, __global HitStats* stats, uint num_hitpoints,
    double alpha, uint volume_stats, __global float2* radius_partials) {
    __local float2 part[PPM_UPDATE_WG];
    uint i = get_global_id(0), lid = get_local_id(0);
    float2 mine = (float2)(0.0f);
    if (i < num_hitpoints) {
        __global const PassFlux* pf = &pass[i];
        __global const HitPoint* hp = &hitpoints[i];
        double3 phi = (double3)((double)pf->flux[0], (double)pf->flux[1], (double)pf->flux[2]) / FLUX_FIXED_SCALE;
        double3 w = (double3)(hp->weight[0], hp->weight[1], hp->weight[2]);
        /* an unused slot has only its pixel written */
        if (hp->pixel != HITPOINT_NONE) {
            const bool in_volume = hitpoint_in_volume(hp);
            if (!in_volume || volume_stats) ppm_update_stats(&stats[i], (double)pf->m, w * phi, alpha, in_volume);
        }
        float r = (float)sqrt(stats[i].r2);
        mine = (float2)(r, r);
    }
    part[lid] = mine;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint stride = PPM_UPDATE_WG / 2; stride > 0; stride >>= 1) {
        if (lid < stride)
            part[lid] = (float2)(part[lid].x + part[lid + stride].x, fmax(part[lid].y, part[lid + stride].y));
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (lid == 0) radius_partials[get_group_id(0)] = part[0];
}
