/* gather.cl: each hit point collects this pass's photons within its radius R(x) from the grid
 * cells its sphere overlaps (Hachisuka et al. 2008, Sec. 4.2: M(x) and Phi_M), a volume hit point
 * the photons stored in media within its sphere (gather_query.cl VolumeQuery). One work item
 * writes one hit point: no atomics. Each photon is weighted by the BRDF at the hit point. PPPM passes one global radius instead (global_r2 > 0). Photons arriving from behind the surface, or lying on a
 * surface that faces the other way, are rejected, unless the hit point transmits diffusely
 * (gather_faces). */
#include "portability.h"
#include "gather_query.cl"

/* c added to three fixed-point sums (FLUX_FIXED_SCALE): exact, in any order. */
void add_fixed_point(float3 c, long* a0, long* a1, long* a2) {
    *a0 += convert_long_rte((double)c.x * FLUX_FIXED_SCALE);
    *a1 += convert_long_rte((double)c.y * FLUX_FIXED_SCALE);
    *a2 += convert_long_rte((double)c.z * FLUX_FIXED_SCALE);
}

__kernel SCALAR_WORK_ITEMS void gather(GATHER_KERNEL_PARAMS(PassFlux)) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (hp->pixel == HITPOINT_NONE) { /* SPPM/PPPM: this pixel's eye path found no surface */
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
        const VolumeQuery q = volume_query(hp, volume_r2, seed, pass);
        GRID_FOR_EACH_NEAR(g, sorted, starts, q.x, q.r2, {
            if (!photon_in_volume(ph)) continue;
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
    /* A pass traced in several photon batches adds them up: integer sums, so the result is the
     * same as for one batch. */
    if (accumulate) {
        acc0 += out[i].flux[0];
        acc1 += out[i].flux[1];
        acc2 += out[i].flux[2];
        m += out[i].m;
    }
    out[i].flux[0] = acc0;
    out[i].flux[1] = acc1;
    out[i].flux[2] = acc2;
    out[i].m = m;
}
