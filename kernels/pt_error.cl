/* pt_error.cl: the error estimate of the integrators that add one sample per pixel and pass to a
 * running sum (path_trace, and vcm_camera for VCM and BPT). The pass's estimate L_j is the sum's
 * growth and the image is their mean; the path tracer and BPT are unbiased and VCM's merging bias
 * stays within the calibration (bench/ERROR_CALIBRATION.md), so the statistics' bias stays 0 and
 * only the spread of the L_j (Welford, as error_update) bounds the error. ErrorStats.direct_y holds the sum's luminance
 * after the previous pass.
 *
 * With Sobol' points (sobol.cl) the passes are not independent: the mean of 2^m of them is far
 * closer to the truth than their spread says (bench/RESULTS.md, issue 36). At every power-of-two
 * count P the statistics split the passes into their two aligned halves, each a net, with means
 * m_1 and m_2, and keep D = ((m_1 - m_2) / 2)^2, which estimates the variance of the mean of all
 * P (exactly for independent passes; for scrambled nets too large by the factor 2^a - 1 when the
 * variance falls as P^-a). The host pools D over the pixels into the gain over independent
 * passes (ErrorEstimator::estimate). For the path tracer mean_bias holds the sum's luminance at
 * the last power-of-two count, m2_bias that count's D (-1 before P = 2). */
#include "error_bound.cl"

__kernel void pt_error_reset(__global const double* accum, uint n, __global ErrorStats* es) {
    uint p = get_global_id(0);
    if (p >= n) return;
    __global ErrorStats* e = &es[p];
    e->n = e->mean_l = e->m2_l = e->mean_bias = 0.0;
    e->m2_bias = -1.0;
    e->direct_y = error_luminance(accum[3 * p], accum[3 * p + 1], accum[3 * p + 2]);
}

__kernel void pt_error_update(__global const double* accum, uint n, __global ErrorStats* es) {
    uint p = get_global_id(0);
    if (p >= n) return;
    __global ErrorStats* e = &es[p];
    const double y = error_luminance(accum[3 * p], accum[3 * p + 1], accum[3 * p + 2]);
    const double L = y - e->direct_y;
    e->direct_y = y;
    const double k = e->n + 1.0, d = L - e->mean_l;
    e->n = k;
    e->mean_l += d / k;
    e->m2_l += d * (L - e->mean_l);
    const ulong c = (ulong)k;
    if ((c & (c - 1UL)) == 0UL) { /* a power of two */
        if (c >= 2UL) {
            const double y0 = y - k * e->mean_l; /* the sum's luminance when the statistics started */
            const double first = e->mean_bias - y0, second = y - e->mean_bias;
            const double dm = (first - second) / k; /* (m_1 - m_2) / 2 */
            e->m2_bias = dm * dm;
        }
        e->mean_bias = y;
    }
}

/* error_bound for the path tracer: no bias; the sixth value is D (above), -1 while there is none. */
__kernel void pt_error_bound(__global const ErrorStats* es, uint n, double t, __global float8* out) {
    uint i = get_global_id(0);
    if (i >= n) return;
    __global const ErrorStats* e = &es[i];
    const double sigma = e->n >= 2.0 ? sqrt(e->m2_l / (e->n - 1.0) / e->n) : INFINITY;
    const double noise = t * sigma;
    out[i] = (float8)((float)noise, (float)e->mean_l, 0.0f, (float)noise, 0.0f, (float)sigma, (float)e->m2_bias, 0.0f);
}
