/* portability.h: what one OpenCL implementation needs and the others ignore (issue 58).
 *
 * SCALAR_WORK_ITEMS marks a kernel that an implementation must not vectorise across work items.
 * Intel's CPU runtime (2025.x and 2026.x from PyPI) packs 16 work items into the lanes of an
 * AVX-512 register; on path_trace, vcm_light and vcm_camera the packed code gets lane 0 right and
 * lanes 1 to 15 wrong (at 64x64 the image's columns 0, 16, 32 and 48 matched PoCL, every other
 * column did not; the path tracer's mean came out 0.69 of PoCL's, VCM wrote negative pixels).
 * Work-groups of 8 or fewer, CL_CONFIG_USE_VECTORIZER=0 or this attribute each give PoCL's image
 * to rounding (relative MSE 1e-10), and oclgrind finds no uninitialised value or invalid access in
 * these kernels, so the packed code, not the kernel, is at fault. The packed code is also no
 * faster there: the path tracer's passes per second were the same with the vectoriser on or off.
 * tests/implementations_test.cpp renders every integrator on every OpenCL implementation it finds
 * and fails on the one that differs: remove the attribute when it passes without it.
 * cl_intel_vec_len_hint is defined exactly where the attribute is understood. */
#ifndef CLPPM_PORTABILITY_H
#define CLPPM_PORTABILITY_H

#ifdef cl_intel_vec_len_hint
#define SCALAR_WORK_ITEMS __attribute__((intel_vec_len_hint(1)))
#else
#define SCALAR_WORK_ITEMS
#endif

#endif
