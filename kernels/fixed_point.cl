/* fixed_point.cl: sums that many work items add to at once, in 64-bit fixed point, so that the
 * total does not depend on the order they add in (light tracing's splats, kernels/vcm.cl). */
#ifndef CLPPM_FIXED_POINT_CL
#define CLPPM_FIXED_POINT_CL

#if defined(cl_khr_int64_base_atomics) && !defined(CLPPM_NO_INT64_ATOMICS)
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#define CLPPM_INT64_ATOMICS 1
#endif

/* Adds v to *a. Integer addition is exact, so the total is the same in any order. Without
 * cl_khr_int64_base_atomics (or with -DCLPPM_NO_INT64_ATOMICS, for the test), two 32-bit atomics
 * on the words of a little-endian int64: the low word, then the high word with the carry out of
 * the low one; the words are inconsistent only until every addition is done. */
void add_fixed(volatile __global long* a, long v) {
#ifdef CLPPM_INT64_ATOMICS
    atom_add(a, v);
#else
    volatile __global uint* w = (volatile __global uint*)a;
    uint lo = (uint)v, hi = (uint)(v >> 32);
    uint old = atomic_add(&w[0], lo);
    atomic_add(&w[1], hi + (old + lo < old ? 1u : 0u));
#endif
}

#endif
