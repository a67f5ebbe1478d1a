/* iridescence.cl: KHR_materials_iridescence's thin-film Fresnel, the reflectance of a film of
 * index eta2 and thickness d (nm) over a base of Fresnel reflectance F0, seen from a medium of
 * index 1 at cos_1 to the (micro)normal: Belcour and Barla 2017, "A Practical Extension to
 * Microfacet Theory for the Modeling of Varying Iridescence", as the extension's specification
 * and the Khronos sample renderer evaluate it (its Airy sum to second order, with the XYZ
 * sensitivities in Fourier space fitted by Gaussians and taken to linear Rec. 709). The film's
 * reflectance at its two interfaces is Schlick's. tests/iridescence_test.cpp holds a host reference
 * and the closed form at normal incidence. */
#ifndef CLPPM_IRIDESCENCE_CL
#define CLPPM_IRIDESCENCE_CL

#include "sampling.cl"

/* The spectral sensitivities' Fourier transform at optical path difference opd (nm) and phase
 * shift, in linear Rec. 709 (Belcour and Barla 2017, supplemental: evalSensitivity). */
float3 irid_sensitivity(float opd, float3 shift) {
    float phase = 2.0f * PI_F * opd * 1.0e-9f;
    const float3 val = (float3)(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
    const float3 pos = (float3)(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
    const float3 var = (float3)(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
    float3 xyz = val * sqrt(2.0f * PI_F * var) * cos(pos * phase + shift) * exp(-phase * phase * var);
    xyz.x += 9.7470e-14f * sqrt(2.0f * PI_F * 4.5282e+09f) * cos(2.2399e+06f * phase + shift.x) *
             exp(-4.5282e+09f * phase * phase);
    xyz /= 1.0685e-7f;
    return (float3)(3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
                    -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
                    0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z);
}

float irid_schlick(float f0, float c) { return f0 + (1.0f - f0) * pow(clamp(1.0f - c, 0.0f, 1.0f), 5.0f); }

/* The film's reflectance (RGB, at least 0) at cos_1 over a base of Fresnel reflectance f0. */
float3 irid_fresnel(float eta2, float d, float cos_1, float3 f0) {
    /* The film fades to nothing as it thins to 0 (the specification's smoothstep). */
    float t = clamp(d / 0.03f, 0.0f, 1.0f);
    float eta = 1.0f + (eta2 - 1.0f) * (t * t * (3.0f - 2.0f * t));
    float sin2_2 = (1.0f - cos_1 * cos_1) / (eta * eta);
    float cos2_2 = 1.0f - sin2_2;
    if (cos2_2 < 0.0f) return (float3)(1.0f); /* total internal reflection */
    float cos_2 = sqrt(cos2_2);
    /* First interface, air to film. */
    float r0 = (eta - 1.0f) / (eta + 1.0f);
    float R12 = irid_schlick(r0 * r0, cos_1), T121 = 1.0f - R12;
    float phi12 = eta < 1.0f ? PI_F : 0.0f, phi21 = PI_F - phi12;
    /* Second interface, film to base (the base's index from its F0). */
    float3 sf0 = sqrt(clamp(f0, 0.0f, 0.9999f));
    float3 base_ior = (1.0f + sf0) / (1.0f - sf0);
    float3 r1 = (base_ior - eta) / (base_ior + eta);
    float3 R1 = r1 * r1;
    float3 R23 = R1 + (1.0f - R1) * pow(clamp(1.0f - cos_2, 0.0f, 1.0f), 5.0f);
    float3 phi23 = select((float3)(0.0f), (float3)(PI_F), isless(base_ior, (float3)(eta)));
    float opd = 2.0f * eta * d * cos_2;
    float3 phi = phi21 + phi23;
    /* The Airy sum: the direct term, then the first two pairs of interference terms. */
    float3 R123 = clamp(R12 * R23, 1e-5f, 0.9999f);
    float3 r123 = sqrt(R123);
    float3 Rs = T121 * T121 * R23 / (1.0f - R123);
    float3 I = R12 + Rs;
    float3 Cm = Rs - T121;
    Cm *= r123;
    I += Cm * 2.0f * irid_sensitivity(opd, phi);
    Cm *= r123;
    I += Cm * 2.0f * irid_sensitivity(2.0f * opd, 2.0f * phi);
    return fmax(I, (float3)(0.0f));
}

#endif
