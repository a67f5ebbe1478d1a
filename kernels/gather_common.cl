/* gather_common.cl: the one loop of every gather over the hashed grid (gather.cl, and the error
 * estimate's second gather in error_estimate.cl): the cells a hit point's sphere overlaps, the
 * elements stored in them and the acceptance rule. Each gather supplies only what it does with an
 * accepted photon, as SmallVCM's HashGrid::Process takes the query's Process(). */
#ifndef CLPPM_GATHER_COMMON_CL
#define CLPPM_GATHER_COMMON_CL

#include "hash_grid.cl"
#include "hitpoint.cl"

/* Whether element ph (a photon or a light vertex), visited in grid cell `cell`, lies within squared
 * radius r2 of x and in this very cell (a bucket holds other cells too, so an element is counted
 * from its own cell only). Returns the squared distance in *d2. */
bool grid_within(__constant GridInfo* g, __global const GRID_ELEM* ph, float3 x, float r2, int3 cell, float* d2) {
    float3 p = load3g(ph->pos);
    float3 d = p - x;
    *d2 = dot(d, d);
    if (*d2 > r2) return false;
    int3 pc = grid_cell(g, p);
    return pc.x == cell.x && pc.y == cell.y && pc.z == cell.z;
}

/* Surfaces whose normals are more than acos(GATHER_MIN_NORMAL_COS), about 84 degrees, apart are
 * different surfaces: the gather refuses one's photons at the other, and disc_coverage.cl counts
 * such a surface as the end of the disc. With a bound of 0 a perpendicular wall's photons counted or
 * not by the rounding of the octahedral normals (a decoded axis is off by 1.5e-5): the floor of a
 * box took the back wall's photons near the corner but not the side walls'. */
#define GATHER_MIN_NORMAL_COS 0.1f

/* The gather's acceptance beyond grid_within: arriving from the front of a hit point with shading
 * normal n, and lying on a surface that faces the same way. A hit point that transmits diffusely
 * (both_sides, KHR_materials_diffuse_transmission) also takes photons that arrived from behind,
 * on a surface that faces the other way: the back of the same surface. Returns the incoming
 * direction in *wi. */
bool gather_faces(__global const GRID_ELEM* ph, float3 n, bool both_sides, float3* wi) {
    *wi = oct_decode(ph->wi_oct);
    bool front = dot(n, *wi) > 0.0f;
    if (HAS_DIFFUSE_TRANSMISSION && both_sides && !front)
        return dot(n, *wi) < 0.0f && dot(n, oct_decode(ph->normal_oct)) < -GATHER_MIN_NORMAL_COS;
    if (!front) return false;
    return dot(n, oct_decode(ph->normal_oct)) > GATHER_MIN_NORMAL_COS;
}

/* The host sizes grid cells to at least a quarter of the largest radius (PhotonMap::build_grid), so
 * a sphere spans at most 9 cells per axis; this bound, never reached by a valid render, keeps any
 * gather finite in time whatever radius reaches it. */
#define GATHER_MAX_CELLS_PER_AXIS 16

/* Runs the statement(s) `...` for every element stored in the buckets of the grid cells c0 to c1
 * (inclusive, at most GATHER_MAX_CELLS_PER_AXIS per axis) for which keep_ (an expression of `cell`)
 * holds, with `ph` (the element) and `cell` (the cell visited) in scope; a bucket holds other cells'
 * elements too, which `...` must skip. OpenCL C has no lambdas: the per-element action is the
 * macro's body, so every gather runs exactly this loop. */
#define GRID_FOR_EACH_IN_CELLS(g_, sorted_, starts_, c0_, c1_, keep_, ...)                                             \
    do {                                                                                                               \
        const int3 grid_c0_ = (c0_);                                                                                   \
        const int3 grid_c1_ = min((c1_), grid_c0_ + (GATHER_MAX_CELLS_PER_AXIS - 1));                                  \
        for (int cz = grid_c0_.z; cz <= grid_c1_.z; ++cz)                                                              \
            for (int cy = grid_c0_.y; cy <= grid_c1_.y; ++cy)                                                          \
                for (int cx = grid_c0_.x; cx <= grid_c1_.x; ++cx) {                                                    \
                    const int3 cell = (int3)(cx, cy, cz);                                                              \
                    if (!(keep_)) continue;                                                                            \
                    const uint grid_b_ = grid_bucket(g_, cell);                                                        \
                    const uint grid_end_ = (starts_)[grid_b_ + 1];                                                     \
                    for (uint grid_k_ = (starts_)[grid_b_]; grid_k_ < grid_end_; ++grid_k_) {                          \
                        __global const GRID_ELEM* ph = &(sorted_)[grid_k_];                                            \
                        __VA_ARGS__                                                                                    \
                    }                                                                                                  \
                }                                                                                                      \
    } while (0)

/* Runs the statement(s) `...` for every element of the grid within squared radius r2 of x
 * (grid_within), with `ph` (the element) and `d2` (its squared distance) in scope. */
#define GRID_FOR_EACH_NEAR(g_, sorted_, starts_, x_, r2_, ...)                                                         \
    do {                                                                                                               \
        const float gather_r_ = sqrt(r2_);                                                                             \
        GRID_FOR_EACH_IN_CELLS(g_, sorted_, starts_, grid_cell(g_, (x_)-gather_r_), grid_cell(g_, (x_) + gather_r_),   \
                               true, {                                                                                 \
                                   float d2;                                                                           \
                                   if (!grid_within(g_, ph, x_, r2_, cell, &d2)) continue;                             \
                                   __VA_ARGS__                                                                         \
                               });                                                                                     \
    } while (0)

/* GRID_FOR_EACH_NEAR with the gather's acceptance (gather_faces) for a hit point with normal n that
 * takes photons from both sides or not; `wi` (the photon's incoming direction) is in scope as well. */
#define GATHER_FOR_EACH_PHOTON(g_, sorted_, starts_, x_, n_, both_, r2_, ...)                                          \
    GRID_FOR_EACH_NEAR(g_, sorted_, starts_, x_, r2_, {                                                                \
        float3 wi;                                                                                                     \
        if (!gather_faces(ph, n_, both_, &wi)) continue;                                                               \
        __VA_ARGS__                                                                                                    \
    })

#endif
