/* gather_common.cl: the photon acceptance rule of a gather over the hashed grid (gather.cl),
 * for further gathers over the same grid (error_estimate.cl) to apply the very same rule. */
#ifndef CLPPM_GATHER_COMMON_CL
#define CLPPM_GATHER_COMMON_CL

#include "hash_grid.cl"
#include "hitpoint.cl"

/* Whether photon ph, visited in grid cell `cell`, counts for a hit point at x with shading normal
 * n and squared radius r2: within the sphere, stored in this very cell (a bucket holds other cells
 * too, so a photon is counted from its own cell only), arriving from the front, and lying on a
 * surface that faces the same way. Returns the squared distance in *d2 and the photon's incoming
 * direction in *wi. */
bool gather_accepts(__constant GridInfo* g, __global const Photon* ph, float3 x, float3 n, float r2, int3 cell,
                    float* d2, float3* wi) {
    float3 p = load3g(ph->pos);
    float3 d = p - x;
    *d2 = dot(d, d);
    if (*d2 > r2) return false;
    int3 pc = grid_cell(g, p);
    if (pc.x != cell.x || pc.y != cell.y || pc.z != cell.z) return false;
    *wi = oct_decode(ph->wi_oct);
    if (dot(n, *wi) <= 0.0f) return false;
    return dot(n, oct_decode(ph->normal_oct)) > 0.0f;
}

#endif
