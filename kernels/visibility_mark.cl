/* visibility_mark.cl: where this pass's hit points may gather a photon, for visual importance
 * (kernels/photon_chain.cl): every cell of a hashed grid that a hit point's sphere overlaps is
 * marked, in a table of bytes. A photon whose cell is unmarked lies farther than R(x) from every
 * hit point (grid_cell is monotone), so PHOTON_SEEN (photon_trace.cl) never drops a photon that a
 * gather would count; hash collisions only mark more. Every writer stores the same 1: no atomics. */
#ifndef CLPPM_VISIBILITY_MARK_CL
#define CLPPM_VISIBILITY_MARK_CL

#include "portability.h"
#include "hash_grid.cl"

/* Marks the cells that hit point i's sphere (radius R(x), or global_r2's) overlaps: a photon
 * outside them is gathered by no hit point of this pass. */
__kernel SCALAR_WORK_ITEMS void visibility_mark(__constant GridInfo* g, __global const HitPoint* hitpoints,
                                                __global const HitStats* stats, uint n, float global_r2,
                                                __global uchar* seen) {
    uint i = get_global_id(0);
    if (i >= n) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (hp->pixel == HITPOINT_NONE) return;
    /* A thousandth wider: rounding in sqrt and x - r never drops a photon the gather keeps. */
    const float r = sqrt(global_r2 > 0.0f ? global_r2 : (float)stats[i].r2) * 1.001f;
    const float3 x = load3g(hp->pos);
    const int3 lo = grid_cell(g, x - r), hi = grid_cell(g, x + r);
    for (int cz = lo.z; cz <= hi.z; ++cz)
        for (int cy = lo.y; cy <= hi.y; ++cy)
            for (int cx = lo.x; cx <= hi.x; ++cx) seen[grid_bucket(g, (int3)(cx, cy, cz))] = 1;
}

#endif
