/* error_estimate.cl: the progressive error estimate of Hachisuka, Jarosz and Jensen, "A Progressive
 * Error Estimation Framework for Photon Density Estimation" (SIGGRAPH Asia 2010), for SPPM and
 * PPPM and PPM, per pixel and on the pixel luminance:
 *   error bound  E_i = |B_i| + t_{i-1}((1 + P) / 2) sqrt(V_i / i)     (Sec. 4: bias plus a stochastic
 *                                                                   noise bound at confidence P)
 *   bias         B_i = mean_j(R_j^2 / 8 * Lap_j L)                  (Sec. 5: B = R^2 k_2 Lap L / 2;
 *                                                                   the disc kernel has k_2 = 1/4)
 *   Laplacian    Lap L ~ mean_j [ sum_p Lap K_R(x - x_p) f Phi_p ]  (Sec. 5: the Laplacian of a smooth
 *                                                                   kernel, accumulated progressively)
 *   variance     V_i = sample variance of the single-pass estimates L_j (Sec. 6)
 * The Laplacian uses the biweight K(t) = 3/pi (1 - |t|^2)^2, whose Laplacian in the plane is
 * 24/pi (2|t|^2 - 1) (K and K' vanish at |t| = 1, so no boundary term). Per pixel for SPPM and
 * PPPM (one visible point each) and for PPM (a pixel's spp fixed hit points); only launched when
 * error estimation is on. */
#include "portability.h"
#include "error_bound.cl"
#include "gather_query.cl"
#include "radiance_estimate.cl"
#include "dispersion.cl"

/* A second gather over this pass's grid, with gather's arguments and photons: per hit point the
 * sum over accepted photons of (2 rho^2 - 1) Y(w f Phi_p), rho = |x_p - x| / R, in fixed point
 * (FLUX_FIXED_SCALE) so the sum does not depend on the visiting order; 24 / (pi R^4) times it is
 * the pass's Laplacian estimate (error_update). One writer per hit point. */
__kernel SCALAR_WORK_ITEMS void error_gather(GATHER_KERNEL_PARAMS(long)) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    long acc = accumulate ? out[i] : 0;
    /* A volume hit point's light joins its pixel's direct sum (sppm.cl volume_accumulate), whose
     * passes' spread error_update takes, or, PPM's, its own statistics; no Laplacian is estimated
     * for it (its bias is not in the bound). */
    if (hp->pixel != HITPOINT_NONE && !hitpoint_in_volume(hp)) {
        const GatherQuery q = gather_query(hp, stats, i, global_r2, seed, pass, coverage);
        /* The path throughput folded into the luminance weights: one scalar sum per hit point. */
        float3 wy = (float3)(hp->weight[0] * (float)ERROR_LUMINANCE_R, hp->weight[1] * (float)ERROR_LUMINANCE_G,
                             hp->weight[2] * (float)ERROR_LUMINANCE_B);
        const float d2_mean = coverage[i].y, r2 = q.r2;
        GATHER_QUERY_FOR_EACH_PHOTON(g, sorted, starts, q, {
            float y = dot(wy, gather_photon(&q, ph, wi));
            acc += convert_long_rte((double)(y * (2.0f * d2 / r2 - d2_mean)) * FLUX_FIXED_SCALE);
        });
    }
    out[i] = acc;
}

/* Hit points [first, last) make one pixel: SPPM's one visible point per pixel (pixel_first = 0:
 * hit point p is pixel p), or PPM's fixed hit points, spp samples per pixel, whose pixel owns
 * [pixel_first[p], pixel_first[p + 1]) as in ppm_film. */
uint2 error_pixel_range(__global const uint* pixel_first, uint p) {
    return pixel_first ? (uint2)(pixel_first[p], pixel_first[p + 1]) : (uint2)(p, p + 1);
}

/* The pixel's summed direct light (and SPPM's seen emission), in luminance. */
double error_direct_y(__global const HitStats* stats, uint2 range) {
    double y = 0.0;
    for (uint k = range.x; k < range.y; ++k)
        y += error_luminance(stats[k].direct[0], stats[k].direct[1], stats[k].direct[2]);
    return y;
}

/* Fresh statistics; direct_y starts at the direct light already summed (a resumed render). */
__kernel void error_reset(__global const HitStats* stats, __global const uint* pixel_first, uint n,
                          __global ErrorStats* es) {
    uint p = get_global_id(0);
    if (p >= n) return;
    __global ErrorStats* e = &es[p];
    e->n = e->mean_l = e->m2_l = e->mean_bias = e->m2_bias = 0.0;
    e->direct_y = error_direct_y(stats, error_pixel_range(pixel_first, p));
}

/* After a pass's gathers, before ppm_update (stats[k].r2 is still this pass's R_j^2): the pass's
 * single-pass estimates join the running means. Per hit point k of the pixel,
 *   L_j += Y(w tau_M) P / (M pi R_j^2),   B_j += R_j^2 Lap_j / 8,
 * plus this pass's direct light (and SPPM's seen emission) and PPM's constant seen emission, all
 * divided by the pixel's sample count, so that the image is exactly mean_j L_j (ppm_update keeps
 * tau / R^2 = sum_j tau_M,j / R_j^2). global_r2 > 0: PPPM's radius. */
__kernel void error_update(__global const PassFlux* pass, __global const long* lap, __global const HitPoint* hitpoints,
                           __global const HitStats* stats, __global const uint* pixel_first,
                           __global const float4* emitted, uint n, uint spp, double global_r2, double power_per_photon,
                           __global ErrorStats* es) {
    uint p = get_global_id(0);
    if (p >= n) return;
    __global ErrorStats* e = &es[p];
    const uint2 range = error_pixel_range(pixel_first, p);
    const double direct_y = error_direct_y(stats, range);
    double L = direct_y - e->direct_y, bias_j = 0.0;
    e->direct_y = direct_y;
    if (emitted) L += error_luminance(emitted[p].x, emitted[p].y, emitted[p].z);
    for (uint k = range.x; k < range.y; ++k) {
        __global const HitPoint* hp = &hitpoints[k];
        const double r2 = global_r2 > 0.0 ? global_r2 : stats[k].r2;
        /* SPPM's and PPPM's volume hit points are in the direct sum; PPM's (pixel_first) keep
         * their own statistics, and their pass estimate is over the sphere's volume. */
        const bool in_volume = hitpoint_in_volume(hp);
        if (hp->pixel == HITPOINT_NONE || (in_volume && !pixel_first) || !(r2 > 0.0)) continue;
        __global const PassFlux* pf = &pass[k];
        double tau_y = error_luminance(hp->weight[0] * ((double)pf->flux[0] / FLUX_FIXED_SCALE),
                                       hp->weight[1] * ((double)pf->flux[1] / FLUX_FIXED_SCALE),
                                       hp->weight[2] * ((double)pf->flux[2] / FLUX_FIXED_SCALE));
        if (in_volume) {
            L += tau_y * power_per_photon / (4.0 / 3.0 * M_PI * r2 * sqrt(r2));
            continue;
        }
        L += tau_y * power_per_photon / (M_PI * r2);
        /* R^2 / 8 times the Laplacian 24 / (pi R^4) sum: 3 / (pi R^2) sum. */
        bias_j += (3.0 / M_PI) * ((double)lap[k] / FLUX_FIXED_SCALE) * power_per_photon / r2;
    }
    L /= (double)spp;
    bias_j /= (double)spp;
    /* Welford's update: no cancellation however many passes. */
    const double k = e->n + 1.0, d = L - e->mean_l, db = bias_j - e->mean_bias;
    e->n = k;
    e->mean_l += d / k;
    e->m2_l += d * (L - e->mean_l);
    e->mean_bias += db / k;
    e->m2_bias += db * (bias_j - e->mean_bias);
}

/* PPM: the spread of a pixel's fixed samples. Its spp samples are frozen for the whole render,
 * so the error of their mean as an estimate of the pixel integral (anti-aliasing, texture and
 * edges within the pixel) never decays; the passes' spread (error_update) cannot see it. The
 * sample variance of the samples' current radiance estimates, divided by spp, estimates the
 * variance of that frozen error plus the pixel's noise (each sample's noise is in its
 * estimate). Sample s of pixel p: its seen emission sample_y[p spp + s] plus, for each of its
 * hit points (hit_sample[k] == s, in sample order within the pixel's range), the film's
 * radiance (ppm_film). Out: sqrt(variance / spp), 0 for spp = 1. */
__kernel void error_sample_spread(__global const HitPoint* hitpoints, __global const HitStats* stats,
                                  __global const uint* pixel_first, __global const uint* hit_sample,
                                  __global const float* sample_y, uint n, uint spp, double total_power,
                                  double photons_emitted, double passes, __global float* out) {
    uint p = get_global_id(0);
    if (p >= n) return;
    if (spp < 2) {
        out[p] = 0.0f;
        return;
    }
    uint k = pixel_first[p];
    const uint end = pixel_first[p + 1];
    double mean = 0.0, m2 = 0.0;
    for (uint s = 0; s < spp; ++s) {
        double y = sample_y[(ulong)p * spp + s];
        for (; k < end && hit_sample[k] == s; ++k) {
            __global const HitStats* st = &stats[k];
            double3 L = hitpoint_photon_radiance(&hitpoints[k], st, total_power, photons_emitted);
            if (passes > 0.0) L += (double3)(st->direct[0], st->direct[1], st->direct[2]) / passes;
            y += error_luminance(L.x, L.y, L.z);
        }
        const double d = y - mean;
        mean += d / (double)(s + 1);
        m2 += d * (y - mean);
    }
    out[p] = (float)sqrt(m2 / (double)(spp - 1) / (double)spp);
}
