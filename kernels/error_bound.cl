/* error_bound.cl: what every integrator's progressive error estimate shares (error_estimate.cl for
 * the photon-mapping ones, pt_error.cl for the path tracer): the luminance the estimate works on
 * and the per-pixel bound from the statistics (ErrorStats, kernels/shared_types.h). */
#ifndef CLPPM_ERROR_BOUND_CL
#define CLPPM_ERROR_BOUND_CL

#include "shared_types.h"

#define ERROR_LUMINANCE_R 0.2126
#define ERROR_LUMINANCE_G 0.7152
#define ERROR_LUMINANCE_B 0.0722

double error_luminance(double r, double g, double b) {
    return ERROR_LUMINANCE_R * r + ERROR_LUMINANCE_G * g + ERROR_LUMINANCE_B * b;
}

/* The de-noised bias counts only where the bias estimate is this many of its own standard
 * deviations from zero (about a 95% two-sided test), and is shrunk by as much:
 *   |B| ~ sqrt(max(0, B_est^2 - z^2 Var(B_est))), with the sign of B_est.
 * z = 1 would be unbiased for B^2 before the max, but the max then leaves a pixel without bias a
 * spurious B^2 of E[(chi^2_1 - 1)+] Var(B_est) = 0.48 Var(B_est) on average; the Laplacian's
 * estimate is about three times as noisy as the pixel's own (its weights 3 (2 rho^2 - 1) have
 * mean square 3), so that is a bias of 1.2 sigma_i where there is none, which put plain SPPM's
 * estimate in the skylit room at 2.3 times its actual error. With z = 2 the spurious part is
 * E[(chi^2_1 - 4)+] Var(B_est) = 0.08 Var(B_est) (bench/ERROR_CALIBRATION.md, "The bias term where
 * the photons are few"). */
#define ERROR_BIAS_SIGNIFICANCE 2.0

/* Per pixel, for the Student-t quantile t of the pass count: (E_i, L_i, B_i, t sigma_i), (B_i with
 * its own noise taken out, sigma_i) and sqrt(Var(B_est)). sigma_i = sqrt(V_i / i) is the standard
 * deviation of the mean L_i; E_i is +Inf until two passes give a variance. */
__kernel void error_bound(__global const ErrorStats* es, uint n, double t, __global float8* out) {
    uint i = get_global_id(0);
    if (i >= n) return;
    __global const ErrorStats* e = &es[i];
    const double bias = e->mean_bias;
    const double sigma = e->n >= 2.0 ? sqrt(e->m2_l / (e->n - 1.0) / e->n) : INFINITY;
    const double var_bias = e->n >= 2.0 ? e->m2_bias / (e->n - 1.0) / e->n : INFINITY;
    const double z2 = ERROR_BIAS_SIGNIFICANCE * ERROR_BIAS_SIGNIFICANCE;
    const double bias_clean = copysign(sqrt(fmax(0.0, bias * bias - z2 * var_bias)), bias);
    const double noise = t * sigma;
    out[i] = (float8)((float)(fabs(bias) + noise), (float)e->mean_l, (float)bias, (float)noise, (float)bias_clean,
                      (float)sigma, (float)sqrt(var_bias), 0.0f);
}

#endif
