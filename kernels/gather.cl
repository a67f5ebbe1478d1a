/* gather.cl: each hit point collects this pass's photons within its radius R(x) from the grid
 * cells its sphere overlaps (Hachisuka et al. 2008, Sec. 4.2: M(x) and Phi_M), a volume hit point
 * the photons stored in media within its sphere (gather_query.cl VolumeQuery). One work item
 * writes one hit point: no atomics. A beam (kernels/beam.cl) takes none here. Each photon is weighted by the BRDF at the hit point. PPPM passes one global radius instead (global_r2 > 0). Photons arriving from behind the surface, or lying on a
 * surface that faces the other way, are rejected, unless the hit point transmits diffusely
 * (gather_faces). */
#include "portability.h"
#include "gather_query.cl"

__kernel SCALAR_WORK_ITEMS void gather(GATHER_KERNEL_PARAMS(PassFlux)) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    /* SPPM/PPPM: this pixel's eye path found no surface; a beam's photons are beam_gather's */
    if (hp->pixel == HITPOINT_NONE || hitpoint_is_beam(hp)) {
        if (!accumulate) {
            out[i].flux[0] = out[i].flux[1] = out[i].flux[2] = 0;
            out[i].m = 0;
        }
        return;
    }
    long acc0 = 0, acc1 = 0, acc2 = 0;
    uint m = 0;
    if (hitpoint_in_volume(hp)) {
        /* A volume hit point: the photons stored in media within its sphere (gather_query.cl). */
        const VolumeQuery q = volume_query(hp, stats, i, volume_r2, seed, pass);
        GRID_FOR_EACH_NEAR(g, sorted, starts, q.x, q.r2, {
            if (!photon_in_volume(ph) || photon_medium(ph) != q.medium) continue;
            add_fixed_point(gather_volume_photon(&q, ph), &acc0, &acc1, &acc2);
            ++m;
        });
    } else {
        const GatherQuery q = gather_query(hp, stats, i, global_r2, seed, pass, coverage);
        GATHER_QUERY_FOR_EACH_PHOTON(g, sorted, starts, q, {
            /* tau_M += f(x, w_p, w_o) Phi_p (Eq. 9); the path throughput is applied later. */
            add_fixed_point(gather_photon(&q, ph, wi), &acc0, &acc1, &acc2);
            ++m;
        });
    }
    store_pass_flux(out, i, acc0, acc1, acc2, m, accumulate);
}
