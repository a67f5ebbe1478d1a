/* portability.h: what one OpenCL implementation needs and the others ignore (issue 58).
 *
 * SCALAR_WORK_ITEMS marks a kernel that an implementation should not vectorise across work items:
 * every kernel that traces rays through the BVH or walks the photon grid, whose work items part
 * ways at every branch, and the grid's counting sort, which shares the gather's helpers. Intel's CPU runtime (2026.2 from PyPI) packs 16 work items into the lanes
 * of an AVX-512 register, and on these kernels that is both wrong and slow:
 *   - wrong: on path_trace, vcm_light and vcm_camera the packed code got lane 0 right and lanes 1
 *     to 15 wrong (at 64x64 the columns 0, 16, 32 and 48 matched PoCL and no other did; the path
 *     tracer's mean came out 0.69 of PoCL's, VCM wrote negative pixels). The trigger is the call
 *     of bsdf_pdf_weighted (kernels/bsdf.cl) with a pointer to its caller's private LobeWeights:
 *     forced inline, the packed path tracer is right. oclgrind finds no uninitialised value or
 *     invalid access in path_trace, so the packed code, not the kernel, is at fault;
 *   - slow: packed, the path tracer ran 42 passes per second on the diffuse box at 128 x 128,
 *     against 105 unpacked (PoCL: 105 to 110); SPPM's photon_trace took 1.86 s for four passes
 *     packed, 0.25 s unpacked (PoCL 0.24), and the gather, the eye pass, direct light and the disc
 *     coverage were 1.7 to 4.8 times slower packed; with grid_count and grid_scatter packed (they
 *     alone gained from it, 0.03 s in four passes), PPM's unpacked gather took 1.3 s instead of
 *     0.57 s, the helpers they share being compiled for the packed callers (bench/RESULTS.md,
 *     "Intel's CPU runtime beside PoCL").
 * Kernels without this mark (films, error statistics, the prefix sum) are straight-line per work
 * item. tests/implementations_test.cpp renders every integrator on
 * every OpenCL implementation it finds and fails where one differs.
 * cl_intel_vec_len_hint is defined exactly where the attribute is understood. */
#ifndef CLPPM_PORTABILITY_H
#define CLPPM_PORTABILITY_H

#ifdef cl_intel_vec_len_hint
#define SCALAR_WORK_ITEMS __attribute__((intel_vec_len_hint(1)))
#else
#define SCALAR_WORK_ITEMS
#endif

#endif
