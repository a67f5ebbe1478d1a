/* hash_grid.cl: a uniform grid over this pass's photons, hashed into a table of buckets and
 * built by counting sort (SmallVCM HashGrid::Build): count per bucket, exclusive prefix sum,
 * scatter. The order of photons inside a bucket may vary between runs; the gather's fixed-point
 * sums make the result independent of it. */
#ifndef CLPPM_HASH_GRID_CL
#define CLPPM_HASH_GRID_CL

#include "portability.h"
#include "shared_types.h"
#include "sampling.cl"

/* What the grid holds: photons, or (-DGRID_ELEM=LightVertex) vertex connection and merging's light
 * vertices. Either has pos, normal_oct and wi_oct. */
#ifndef GRID_ELEM
#define GRID_ELEM Photon
#endif

int3 grid_cell(__constant GridInfo* g, float3 p) {
    float3 c = floor((p - load3c(g->origin)) * g->inv_cell);
    /* Clamping keeps far-away points (outside the scene bounds) in range; monotone, so a photon
     * within reach of a hit point still falls in the cell range the hit point visits. */
    c = clamp(c, -1048576.0f, 1048576.0f);
    return convert_int3(c);
}

uint grid_bucket(__constant GridInfo* g, int3 c) {
    uint h = ((uint)c.x * 73856093u) ^ ((uint)c.y * 19349663u) ^ ((uint)c.z * 83492791u);
    return h & (g->table_size - 1u);
}

/* Counts the element at p in its bucket. */
void grid_count_one(__constant GridInfo* g, float3 p, volatile __global uint* counts) {
    atomic_inc(&counts[grid_bucket(g, grid_cell(g, p))]);
}

__kernel SCALAR_WORK_ITEMS void grid_count(__constant GridInfo* g, __global const GRID_ELEM* photons,
                                           volatile __global uint* counts) {
    uint i = get_global_id(0);
    if (i >= g->num_photons) return;
    grid_count_one(g, load3g(photons[i].pos), counts);
}

/* Exclusive prefix sum of n counts into starts[0..n] by one work-group of GRID_SCAN_WG items:
 * each item sums a contiguous chunk, the chunk sums are scanned in local memory, then each item
 * writes its chunk's prefixes. starts[n] is the total. */
__kernel __attribute__((reqd_work_group_size(GRID_SCAN_WG, 1, 1))) void grid_scan(__global const uint* counts,
                                                                                  __global uint* starts, uint n) {
    __local uint partial[GRID_SCAN_WG];
    uint lid = get_local_id(0);
    uint chunk = (n + GRID_SCAN_WG - 1) / GRID_SCAN_WG;
    uint begin = min(n, lid * chunk), end = min(n, begin + chunk);
    uint sum = 0;
    for (uint k = begin; k < end; ++k) sum += counts[k];
    partial[lid] = sum;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (lid == 0) {
        uint run = 0;
        for (uint k = 0; k < GRID_SCAN_WG; ++k) {
            uint v = partial[k];
            partial[k] = run;
            run += v;
        }
        starts[n] = run;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    uint run = partial[lid];
    for (uint k = begin; k < end; ++k) {
        starts[k] = run;
        run += counts[k];
    }
}

/* counts still holds the per-bucket counts; counting down gives each photon a distinct slot. */
void grid_scatter_one(__constant GridInfo* g, const GRID_ELEM* ph, __global const uint* starts,
                      volatile __global uint* counts, __global GRID_ELEM* sorted) {
    uint b = grid_bucket(g, grid_cell(g, load3(ph->pos)));
    uint slot = starts[b] + atomic_dec(&counts[b]) - 1u;
    sorted[slot] = *ph;
}

__kernel SCALAR_WORK_ITEMS void grid_scatter(__constant GridInfo* g, __global const GRID_ELEM* photons,
                                             __global const uint* starts, volatile __global uint* counts,
                                             __global GRID_ELEM* sorted) {
    uint i = get_global_id(0);
    if (i >= g->num_photons) return;
    GRID_ELEM ph = photons[i];
    grid_scatter_one(g, &ph, starts, counts, sorted);
}

#endif
