/* gather_common.cl: the one loop of every gather over the hashed grid (gather.cl, and the error
 * estimate's second gather in error_estimate.cl): the cells a hit point's sphere overlaps, the
 * photons stored in them and the acceptance rule. Each gather supplies only what it does with an
 * accepted photon, as SmallVCM's HashGrid::Process takes the query's Process(). */
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

/* The host sizes grid cells to at least a quarter of the largest radius (PhotonMap::build_grid), so
 * a sphere spans at most 9 cells per axis; this bound, never reached by a valid render, keeps any
 * gather finite in time whatever radius reaches it. */
#define GATHER_MAX_CELLS_PER_AXIS 16

/* Runs the statement(s) `...` for every photon of the grid that gather_accepts for a hit point at
 * x with normal n and squared radius r2, with `ph` (the photon), `d2` (its squared distance) and
 * `wi` (its incoming direction) in scope. OpenCL C has no lambdas: the per-photon action is the
 * macro's body, so every gather runs exactly this loop. */
#define GATHER_FOR_EACH_PHOTON(g, sorted, starts, x, n, r2, ...)                                                    \
    do {                                                                                                           \
        const float gather_r_ = sqrt(r2);                                                                          \
        const int3 gather_c0_ = grid_cell(g, (x) - gather_r_);                                                     \
        const int3 gather_c1_ = min(grid_cell(g, (x) + gather_r_), gather_c0_ + (GATHER_MAX_CELLS_PER_AXIS - 1));  \
        for (int cz = gather_c0_.z; cz <= gather_c1_.z; ++cz)                                                      \
            for (int cy = gather_c0_.y; cy <= gather_c1_.y; ++cy)                                                  \
                for (int cx = gather_c0_.x; cx <= gather_c1_.x; ++cx) {                                            \
                    const int3 cell = (int3)(cx, cy, cz);                                                          \
                    const uint b = grid_bucket(g, cell);                                                           \
                    const uint end = (starts)[b + 1];                                                              \
                    for (uint k = (starts)[b]; k < end; ++k) {                                                     \
                        __global const Photon* ph = &(sorted)[k];                                                  \
                        float d2;                                                                                  \
                        float3 wi;                                                                                 \
                        if (!gather_accepts(g, ph, x, n, r2, cell, &d2, &wi)) continue;                            \
                        __VA_ARGS__                                                                                \
                    }                                                                                              \
                }                                                                                                  \
    } while (0)

#endif
