/* beam.cl: the beam radiance estimate (Jarosz, Zwicker and Jensen 2008, "The Beam Radiance
 * Estimate for Volumetric Photon Mapping", Eq. 11 with a constant 2-D kernel), made progressive
 * as probabilistic PPM (Knaus and Zwicker 2011) does: SPPM's and PPPM's camera rays through media.
 * A beam (shared_types.h) is a camera ray's segment o + t d, t in [0, t_max], through a medium of
 * extinction sigma_t and albedo sigma_s / sigma_t. The light it scatters towards the camera,
 *   L_b = int_0^t_max sigma_s T(t) L_s(o + t d, -d) dt,
 * is estimated from this pass's photons stored in media (Photon: flux times sigma_t T / pdf of the
 * photon's free flight, so sigma_s L_s ~ sum_p p Phi_p / (sigma_t V), gather_query.cl) within the
 * cylinder of radius r around the segment:
 *   L_b ~ albedo sum_p T(t_p) p(-wi_p . -d) Phi_p / (pi r^2),
 * t_p the photon's distance along the ray and its distance from the ray below r. Where a volume hit
 * point (gather.cl) estimates the integrand at one distance the eye path sampled, the beam takes
 * the whole segment: no distance to sample, every camera ray sees the fog. The direct light along
 * the segment is a light sample at a distance sampled within it (beam_direct_light).
 * The pixels' beams follow their hit points in one buffer (slot num_pixels + i is pixel i's beam);
 * gather.cl leaves beams to beam_gather, which runs over the same slots on PhotonMap's second grid
 * (the photons stored in media, in cells of side 2 r). */
#ifndef CLPPM_BEAM_CL
#define CLPPM_BEAM_CL

#include "gather_query.cl"
#include "direct_light.cl"

/* Bounds that keep any beam gather finite whatever radius and segment reach it: a valid render's
 * steps are at most a cell long, so a step's cells span at most 3 per axis with cells of side 2 r. */
#define BEAM_MAX_STEPS 4096u

/* PhotonMap's grid for beams holds the photons stored in media alone (HashGrid "beam_"). */
__kernel SCALAR_WORK_ITEMS void beam_grid_count(__constant GridInfo* g, __global const Photon* photons,
                                                volatile __global uint* counts) {
    const uint i = get_global_id(0);
    if (i < g->num_photons && photon_in_volume(&photons[i])) grid_count_one(g, load3g(photons[i].pos), counts);
}

__kernel SCALAR_WORK_ITEMS void beam_grid_scatter(__constant GridInfo* g, __global const Photon* photons,
                                                  __global const uint* starts, volatile __global uint* counts,
                                                  __global Photon* sorted) {
    const uint i = get_global_id(0);
    if (i >= g->num_photons || !photon_in_volume(&photons[i])) return;
    const Photon ph = photons[i];
    grid_scatter_one(g, &ph, starts, counts, sorted);
}

/* Whether grid cell c (of side `side` from `origin`) may hold a point within r of the line o + t d:
 * its centre lies within r and half its diagonal of the line (with a margin for rounding). */
bool beam_cell_near(int3 c, float3 origin, float side, float3 o, float3 d, float r) {
    const float3 w = origin + (convert_float3(c) + 0.5f) * side - o;
    const float3 e = w - d * dot(w, d);
    const float reach = r + 0.87f * side;
    return dot(e, e) <= reach * reach;
}

/* Sum over the pass's photons in media within the cylinder of squared radius r2 around beam hp of
 * T(t_p) p Phi_p (the albedo and 1 / (pi r^2) are beam_accumulate's), into out as gather does. The
 * segment is walked in steps no longer than a cell; a step visits the cells of its piece's box
 * grown by r that come near enough the line (beam_cell_near) and takes the photons whose t_p falls
 * in the step, so each photon is counted once. */
__kernel SCALAR_WORK_ITEMS void beam_gather(__constant GridInfo* g, __global const Photon* sorted,
                                            __global const uint* starts, __global const HitPoint* hitpoints,
                                            uint num_hitpoints, float beam_r2, uint accumulate, __global PassFlux* out,
                                            ulong seed, ulong pass) {
    const uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (hp->pixel == HITPOINT_NONE || !hitpoint_is_beam(hp)) return; /* gather wrote it */
    const float3 o = load3g(hp->pos), d = load3g(hp->f0), sigma = load3g(hp->color);
    const float t_max = hp->dielectric, hg_g = hp->f90, r = sqrt(beam_r2);
    const PassWavelength pw = pass_wavelength(seed, pass);
    const bool dispersed = hitpoint_dispersed(hp);
    const uint medium = hitpoint_medium(hp);
    const float steps_f = ceil(t_max * g->inv_cell);
    const uint steps = steps_f >= (float)BEAM_MAX_STEPS ? BEAM_MAX_STEPS : max(1u, (uint)steps_f);
    const float h = t_max / (float)steps, side = 1.0f / g->inv_cell;
    const float3 origin = load3c(g->origin);
    long acc0 = 0, acc1 = 0, acc2 = 0;
    uint m = 0;
    for (uint k = 0; k < steps; ++k) {
        const bool last = k + 1 == steps;
        const float t0 = h * (float)k, t1 = last ? t_max : h * (float)(k + 1);
        const float3 a = o + d * t0, b = o + d * t1;
        GRID_FOR_EACH_IN_CELLS(g, sorted, starts, grid_cell(g, fmin(a, b) - r), grid_cell(g, fmax(a, b) + r),
                               beam_cell_near(cell, origin, side, o, d, r), {
                                   const float3 p = load3g(ph->pos);
                                   const int3 pc = grid_cell(g, p);
                                   if (pc.x != cell.x || pc.y != cell.y || pc.z != cell.z)
                                       continue;                              /* another cell's, same bucket */
                                   if (photon_medium(ph) != medium) continue; /* across a boundary */
                                   const float tp = dot(p - o, d);
                                   if (!(tp >= t0 && (tp < t1 || (last && tp <= t_max)))) continue;
                                   const float3 v = p - (o + d * tp);
                                   if (dot(v, v) > beam_r2) continue;
                                   const float3 wi = oct_decode(ph->wi_oct);
                                   add_fixed_point(volume_photon_flux(ph, dispersed, &pw) *
                                                       medium_transmittance(sigma, tp) * hg_phase(dot(wi, d), hg_g),
                                                   &acc0, &acc1, &acc2);
                                   ++m;
                               });
    }
    store_pass_flux(out, i, acc0, acc1, acc2, m, accumulate);
}

/* Pixel i's beam (slot n + i) joins its running sum of direct light: albedo times the gathered sum
 * times scale = P / (M pi r^2), the photons' flux in units of P over the kernel's area. */
__kernel void beam_accumulate(__global const PassFlux* pass, __global const HitPoint* hitpoints,
                              __global HitStats* stats, uint n, double scale) {
    const uint i = get_global_id(0);
    if (i >= n) return;
    __global const HitPoint* hp = &hitpoints[n + i];
    __global const PassFlux* f = &pass[n + i];
    if (f->m == 0 || hp->pixel == HITPOINT_NONE || !hitpoint_is_beam(hp)) return;
    for (int c = 0; c < 3; ++c)
        stats[i].direct[c] +=
            (double)hp->weight[c] * (double)hp->sheen[c] * ((double)f->flux[c] / FLUX_FIXED_SCALE) * scale;
}

/* The direct light pixel i's beam (slot n + i) scatters towards the camera, at a distance sampled
 * within the segment in proportion to sigma_t T (medium_sample_within): volume_direct_light's light
 * and phase samples there. The photons carry the rest. */
__kernel SCALAR_WORK_ITEMS void beam_direct_light(SCENE_PARAMS, ulong seed, ulong pass,
                                                  __global const HitPoint* hitpoints, __global HitStats* stats,
                                                  uint n) {
    const uint i = get_global_id(0);
    if (i >= n) return;
    __global const HitPoint* hp = &hitpoints[n + i];
    if (hp->pixel == HITPOINT_NONE || !hitpoint_is_beam(hp)) return;
    Rng rng = rng_make(seed, pass, n + i, RNG_DIRECT);
    Medium m;
    m.sigma_t = load3g(hp->color);
    m.albedo = load3g(hp->sheen);
    m.g = hp->f90;
    m.id = hitpoint_medium(hp);
    float3 w = load3g(hp->weight);
    float t;
    const float u0 = rng_float(&rng), u1 = rng_float(&rng);
    if (!medium_sample_within(&m, hp->dielectric, (float2)(u0, u1), &w, &t)) return;
    const float3 x = load3g(hp->pos) + load3g(hp->f0) * t;
    const float3 L = w * m.albedo * volume_direct_light(SCENE_ARGS, hp, x, &rng);
    stats[i].direct[0] += L.x;
    stats[i].direct[1] += L.y;
    stats[i].direct[2] += L.z;
}

#endif
