/* pt_error.cl: the path tracer's error estimate. A pass adds one sample per pixel to the running
 * sum (path_trace), so the pass's estimate L_j is the sum's growth and the image is their mean;
 * the estimate is unbiased, so the statistics' bias stays 0 and only the spread of the L_j
 * (Welford, as error_update) bounds the error. ErrorStats.direct_y holds the sum's luminance
 * after the previous pass. */
#include "error_bound.cl"

__kernel void pt_error_reset(__global const double* accum, uint n, __global ErrorStats* es) {
    uint p = get_global_id(0);
    if (p >= n) return;
    __global ErrorStats* e = &es[p];
    e->n = e->mean_l = e->m2_l = e->mean_bias = e->m2_bias = 0.0;
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
}
