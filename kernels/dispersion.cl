/* dispersion.cl: spectral transport for KHR_materials_dispersion, paid for only by scenes that
 * disperse (HAS_DISPERSION; docs/scenes.md, "dispersion").
 *
 * Light stays RGB everywhere except where it crosses a dispersive dielectric, whose index depends
 * on the wavelength (the extension's Cauchy form, dispersion_ior). Every pass draws one wavelength
 * lambda_k for all of its paths, photons and eye paths alike (pass_wavelength): stratified over
 * the passes by the golden-ratio sequence, in proportion to how much of white light's RGB lies
 * there (kernels/wavelength_table.h, scripts/make_wavelength_table.py). A path that meets a
 * dispersive surface takes the refractive index at lambda_k there and, the first time, the weight
 * W_k = w(lambda_k) / p(lambda_k): the RGB colour of that wavelength of white light over its
 * probability, whose expectation over the passes is exactly (1, 1, 1). So
 *  - a path that never meets dispersion is unchanged, bit for bit, and costs no extra noise;
 *  - a photon and an eye path of the same pass always share a wavelength, so a merge (a photon at
 *    a hit point, a VCM merge or connection) joins two halves of one physical path: when both
 *    halves were dispersed, each carries W_k and the pair is divided by it once (merge_dispersion);
 *  - one wavelength per pass, not per path: per-path wavelengths (hero wavelengths, Wilkie et al.
 *    2014) would give each photon its own wavelength, which no eye path of another wavelength may
 *    merge with. Each pixel still sees one wavelength per pass, as with per-path sampling, and the
 *    sequence over passes is stratified.
 * Whether a path has been dispersed travels with what it stores: the sign bit of a photon's
 * flux[0], of a light vertex's throughput[0] and of a hit point's footprint (all non-negative
 * otherwise). Without HAS_DISPERSION every function here is the identity or false. */
#ifndef CLPPM_DISPERSION_CL
#define CLPPM_DISPERSION_CL

#include "bsdf.cl"
#include "wavelength_table.h"

/* The golden ratio's fractional part: u_k = frac(u_0 + k phi) is stratified over any run of
 * passes (Weyl's sequence). */
#define DISPERSION_PHI 0.61803398874989485f

/* KHR_materials_dispersion: n(lambda) = max(n_d + (n_d - 1) / V_d (523655 / lambda^2 - 1.5168), 1),
 * V_d = 20 / dispersion the Abbe number, lambda in nm (the Cauchy form through n_d at 587.6 nm with
 * n_F - n_C = (n_d - 1) / V_d). */
float dispersion_ior(float n_d, float dispersion, float lambda) {
    return fmax(n_d + (n_d - 1.0f) * dispersion * (1.0f / 20.0f) * (523655.0f / (lambda * lambda) - 1.5168f), 1.0f);
}

/* This pass's wavelength (nm), its weight W and, per channel, 1 / W (0 where W is 0). */
typedef struct {
    float lambda;
    float3 weight, inv_weight;
} PassWavelength;

/* The wavelength of u in [0, 1): the bin whose cumulative probability first exceeds u, and within
 * it the position of u between the bin's ends (uniform in the bin). */
PassWavelength wavelength_at(float u) {
    int lo = 0, hi = WAVELENGTH_BINS - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (u < wavelength_cdf[mid]) hi = mid;
        else lo = mid + 1;
    }
    float c0 = lo > 0 ? wavelength_cdf[lo - 1] : 0.0f, c1 = wavelength_cdf[lo];
    float t = c1 > c0 ? clamp((u - c0) / (c1 - c0), 0.0f, 1.0f) : 0.5f;
    PassWavelength pw;
    pw.lambda = (float)(WAVELENGTH_MIN + lo) - 0.5f + t;
    pw.weight = (float3)(wavelength_weight[3 * lo], wavelength_weight[3 * lo + 1], wavelength_weight[3 * lo + 2]);
    pw.inv_weight = select((float3)(0.0f), 1.0f / pw.weight, pw.weight > 0.0f);
    return pw;
}

/* Pass k's wavelength under seed: u_k = frac(u_0(seed) + k phi), the same in every kernel of the
 * pass and on every device. */
PassWavelength pass_wavelength(ulong seed, ulong pass) {
    if (!HAS_DISPERSION) { /* never read: every use is behind HAS_DISPERSION */
        PassWavelength none;
        none.lambda = 0.0f;
        none.weight = none.inv_weight = (float3)(1.0f);
        return none;
    }
    ulong h = seed * 0x9E3779B97F4A7C15UL;
    h ^= h >> 29;
    float u0 = (float)(h >> 40) * (1.0f / 16777216.0f);
    float k = (float)(pass % 16777216UL);
    float u = u0 + k * DISPERSION_PHI;
    u -= floor(u);
    return wavelength_at(fmin(u, 0.99999994f));
}

/* Whether the material at s disperses: a dispersion above 0 on a volume (KHR_materials_dispersion
 * builds on KHR_materials_volume; a thin wall does not bend light) that transmits. */
bool surface_disperses(SCENE_PARAMS, const Surface* s, const Bsdf* b) {
    if (!HAS_DISPERSION || !(b->glass > 0.0f) || b->thin) return false;
    return materials[s->material].dispersion > 0.0f;
}

/* At a dispersive surface, the relative index at this pass's wavelength (a surface rebuilt from a
 * stored vertex). Returns whether the surface disperses. */
bool disperse_index(SCENE_PARAMS, const Surface* s, Bsdf* b, const PassWavelength* pw) {
    if (!surface_disperses(SCENE_ARGS, s, b)) return false;
    __global const Material* m = &materials[s->material];
    float n = dispersion_ior(m->ior, m->dispersion, pw->lambda);
    b->eta = s->front ? n : 1.0f / n;
    return true;
}

/* At a dispersive surface: the index at this pass's wavelength, and, on the path's first
 * dispersive surface, its weight W on the path's throughput. Returns whether the surface
 * disperses. */
bool disperse(SCENE_PARAMS, const Surface* s, Bsdf* b, const PassWavelength* pw, bool* dispersed, float3* throughput) {
    if (!disperse_index(SCENE_ARGS, s, b, pw)) return false;
    if (!*dispersed) {
        *throughput *= pw->weight;
        *dispersed = true;
    }
    return true;
}

/* The factor on a merge or connection of two halves: 1 / W when both were dispersed (each
 * carries W once), else 1. */
float3 merge_dispersion(bool a, bool b, const PassWavelength* pw) {
    return HAS_DISPERSION && a && b ? pw->inv_weight : (float3)(1.0f);
}

/* The dispersed flag in the sign bit of a non-negative float. */
float with_dispersed(float x, bool dispersed) {
    return HAS_DISPERSION && dispersed ? as_float(as_uint(x) | 0x80000000u) : x;
}
bool is_dispersed(float x) { return HAS_DISPERSION && (as_uint(x) >> 31) != 0u; }
float without_dispersed(float x) { return HAS_DISPERSION ? as_float(as_uint(x) & 0x7fffffffu) : x; }

/* Whether the eye path of a hit point was dispersed (the sign of its footprint). */
bool hitpoint_dispersed(__global const HitPoint* hp) { return is_dispersed(hp->footprint); }

/* A stored element's RGB with its flag taken off (a photon's flux, a light vertex's throughput). */
float3 load3_dispersed(__global const float* v) { return (float3)(without_dispersed(v[0]), v[1], v[2]); }

#endif
