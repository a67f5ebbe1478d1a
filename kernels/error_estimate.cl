/* error_estimate.cl: the progressive error estimate of Hachisuka, Jarosz and Jensen, "A Progressive
 * Error Estimation Framework for Photon Density Estimation" (SIGGRAPH Asia 2010), for SPPM and
 * PPPM, per pixel and on the pixel luminance:
 *   error bound  E_i = |B_i| + t_{i-1}((1 + P) / 2) sqrt(V_i / i)     (Sec. 4: bias plus a stochastic
 *                                                                   noise bound at confidence P)
 *   bias         B_i = mean_j(R_j^2) / 8 * Lap L                    (Sec. 5: B = R^2 k_2 Lap L / 2;
 *                                                                   the disc kernel has k_2 = 1/4)
 *   Laplacian    Lap L ~ mean_j [ sum_p Lap K_R(x - x_p) f Phi_p ]  (Sec. 5: the Laplacian of a smooth
 *                                                                   kernel, accumulated progressively)
 *   variance     V_i = sample variance of the single-pass estimates L_j (Sec. 6)
 * The Laplacian uses the biweight K(t) = 3/pi (1 - |t|^2)^2, whose Laplacian in the plane is
 * 24/pi (2|t|^2 - 1) (K and K' vanish at |t| = 1, so no boundary term). Only compiled into the
 * SPPM program; only launched when error estimation is on. */
#include "gather_common.cl"

#define ERROR_LUMINANCE_R 0.2126
#define ERROR_LUMINANCE_G 0.7152
#define ERROR_LUMINANCE_B 0.0722

double error_luminance(double r, double g, double b) {
    return ERROR_LUMINANCE_R * r + ERROR_LUMINANCE_G * g + ERROR_LUMINANCE_B * b;
}

/* A second gather over this pass's grid, with gather's arguments and photons: per hit point the
 * sum over accepted photons of (2 rho^2 - 1) Y(w f Phi_p), rho = |x_p - x| / R, in fixed point
 * (FLUX_FIXED_SCALE) so the sum does not depend on the visiting order; 24 / (pi R^4) times it is
 * the pass's Laplacian estimate (error_update). One writer per hit point. */
__kernel void error_gather(__constant GridInfo* g, __global const Photon* sorted, __global const uint* starts,
                           __global const HitPoint* hitpoints, __global const HitStats* stats, uint num_hitpoints,
                           float global_r2, uint accumulate, __global long* out) {
    uint i = get_global_id(0);
    if (i >= num_hitpoints) return;
    __global const HitPoint* hp = &hitpoints[i];
    long acc = accumulate ? out[i] : 0;
    if (hp->pixel != HITPOINT_NONE) {
        float3 x = load3g(hp->pos), n = oct_decode(hp->normal_oct);
        HitBrdf brdf = hitpoint_brdf_make(hp, n);
        float r2 = global_r2 > 0.0f ? global_r2 : (float)stats[i].r2;
        /* The path throughput folded into the luminance weights: one scalar sum per hit point. */
        float3 wy = (float3)(hp->weight[0] * (float)ERROR_LUMINANCE_R, hp->weight[1] * (float)ERROR_LUMINANCE_G,
                             hp->weight[2] * (float)ERROR_LUMINANCE_B);
        GATHER_FOR_EACH_PHOTON(g, sorted, starts, x, n, r2, {
            float3 f = hitpoint_brdf(&brdf, wi);
            float y = dot(wy, f * load3g(ph->flux));
            acc += convert_long_rte((double)(y * (2.0f * d2 / r2 - 1.0f)) * FLUX_FIXED_SCALE);
        });
    }
    out[i] = acc;
}

/* Fresh statistics; direct_y starts at the direct light already summed (a resumed render). */
__kernel void error_reset(__global const HitStats* stats, uint n, __global ErrorStats* es) {
    uint i = get_global_id(0);
    if (i >= n) return;
    __global const HitStats* s = &stats[i];
    __global ErrorStats* e = &es[i];
    e->n = e->mean_l = e->m2_l = e->mean_r2 = e->mean_lap = 0.0;
    e->direct_y = error_luminance(s->direct[0], s->direct[1], s->direct[2]);
}

/* After a pass's gathers, before ppm_update (stats[i].r2 is still this pass's R_j^2): the pass's
 * single-pass estimates join the running means. L_j = Y(w tau_M) P / (M pi R_j^2) + this pass's
 * emission and direct light, so that the image is mean_j L_j. global_r2 > 0: PPPM's radius. */
__kernel void error_update(__global const PassFlux* pass, __global const long* lap, __global const HitPoint* hitpoints,
                           __global const HitStats* stats, uint n, double global_r2, double power_per_photon,
                           __global ErrorStats* es) {
    uint i = get_global_id(0);
    if (i >= n) return;
    __global const HitStats* s = &stats[i];
    __global ErrorStats* e = &es[i];
    const double r2 = global_r2 > 0.0 ? global_r2 : s->r2;
    const double direct_y = error_luminance(s->direct[0], s->direct[1], s->direct[2]);
    double L = direct_y - e->direct_y, lap_j = 0.0;
    e->direct_y = direct_y;
    __global const HitPoint* hp = &hitpoints[i];
    if (hp->pixel != HITPOINT_NONE && r2 > 0.0) {
        __global const PassFlux* pf = &pass[i];
        double tau_y = error_luminance(hp->weight[0] * ((double)pf->flux[0] / FLUX_FIXED_SCALE),
                                       hp->weight[1] * ((double)pf->flux[1] / FLUX_FIXED_SCALE),
                                       hp->weight[2] * ((double)pf->flux[2] / FLUX_FIXED_SCALE));
        L += tau_y * power_per_photon / (M_PI * r2);
        lap_j = (24.0 / M_PI) * ((double)lap[i] / FLUX_FIXED_SCALE) * power_per_photon / (r2 * r2);
    }
    /* Welford's update: no cancellation however many passes. */
    const double k = e->n + 1.0, d = L - e->mean_l;
    e->n = k;
    e->mean_l += d / k;
    e->m2_l += d * (L - e->mean_l);
    e->mean_r2 += (r2 - e->mean_r2) / k;
    e->mean_lap += (lap_j - e->mean_lap) / k;
}

/* Per pixel (E_i, L_i, B_i, noise bound) for the Student-t quantile t of the pass count; E_i is
 * +Inf until two passes give a variance. */
__kernel void error_bound(__global const ErrorStats* es, uint n, double t, __global float4* out) {
    uint i = get_global_id(0);
    if (i >= n) return;
    __global const ErrorStats* e = &es[i];
    const double bias = e->mean_r2 * e->mean_lap / 8.0;
    const double noise = e->n >= 2.0 ? t * sqrt(e->m2_l / (e->n - 1.0) / e->n) : INFINITY;
    out[i] = (float4)((float)(fabs(bias) + noise), (float)e->mean_l, (float)bias, (float)noise);
}
