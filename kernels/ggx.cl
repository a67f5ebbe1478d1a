/* ggx.cl: the GGX (Trowbridge-Reitz) microfacet reflection lobe with the height-correlated
 * Smith shadowing and Schlick's Fresnel, as glTF's metal and specular layer use it (alpha =
 * roughness^2; kernels/bsdf.cl combines the lobes). Sampled by the distribution of visible normals (Heitz 2018,
 * "Sampling the GGX Distribution of Visible Normals"). All directions point away from the
 * surface; n is the shading normal on the side of wo. tests/bsdf_test.cpp holds the host
 * reference. */
#ifndef CLPPM_GGX_CL
#define CLPPM_GGX_CL

#include "sampling.cl"

/* D(h), Walter et al. 2007 Eq. 33, with cos_h = n.h. */
float ggx_d(float cos_h, float alpha) {
    float a2 = alpha * alpha;
    /* (1 - c^2) + c^2 a2, not c^2 (a2 - 1) + 1: for alpha below ~1.7e-4, a2 - 1 rounds to -1 and
     * D would be infinite at the peak. */
    float c2 = cos_h * cos_h;
    float t = (1.0f - c2) + c2 * a2;
    return a2 / (PI_F * t * t);
}

/* Smith's Lambda for GGX (Heitz 2014, Eq. 72). */
float ggx_lambda(float cos_v, float alpha) {
    float c2 = cos_v * cos_v;
    float tan2 = fmax(0.0f, 1.0f - c2) / fmax(c2, 1e-12f);
    return 0.5f * (-1.0f + sqrt(1.0f + alpha * alpha * tan2));
}

float ggx_g1(float cos_v, float alpha) { return 1.0f / (1.0f + ggx_lambda(cos_v, alpha)); }

/* Height-correlated masking-shadowing G2 (Heitz 2014, Eq. 99). */
float ggx_g2(float cos_o, float cos_i, float alpha) {
    return 1.0f / (1.0f + ggx_lambda(cos_o, alpha) + ggx_lambda(cos_i, alpha));
}

float3 fresnel_schlick(float3 f0, float cos_d) {
    float m = clamp(1.0f - cos_d, 0.0f, 1.0f);
    float m5 = m * m * m * m * m;
    return f0 + (1.0f - f0) * m5;
}

/* f(wo, wi) = D G2 F / (4 cos_o cos_i); zero below the surface. */
float3 ggx_eval(float3 n, float3 wo, float3 wi, float3 f0, float alpha) {
    float cos_o = dot(n, wo), cos_i = dot(n, wi);
    if (cos_o <= 0.0f || cos_i <= 0.0f) return (float3)(0.0f);
    float3 h = normalize(wo + wi);
    float d = ggx_d(dot(n, h), alpha);
    float g = ggx_g2(cos_o, cos_i, alpha);
    return fresnel_schlick(f0, dot(wi, h)) * (d * g / (4.0f * cos_o * cos_i));
}

/* pdf of ggx_sample over wi (solid angle): D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 cos_o). */
float ggx_pdf(float3 n, float3 wo, float3 wi, float alpha) {
    float cos_o = dot(n, wo), cos_i = dot(n, wi);
    if (cos_o <= 0.0f || cos_i <= 0.0f) return 0.0f;
    float3 h = normalize(wo + wi);
    return ggx_g1(cos_o, alpha) * ggx_d(dot(n, h), alpha) / (4.0f * cos_o);
}

/* A microfacet normal by the visible normals seen from v, in the local frame (t, b, n) of the
 * lobe, stretched by alpha_x along t and alpha_y along b (Heitz 2018, listing 1). */
float3 ggx_sample_h_aniso(float3 v, float ax, float ay, float u1, float u2) {
    float3 vh = normalize((float3)(ax * v.x, ay * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    float3 T1 = lensq > 0.0f ? (float3)(-vh.y, vh.x, 0.0f) * rsqrt(lensq) : (float3)(1.0f, 0.0f, 0.0f);
    float3 T2 = cross(vh, T1);
    float r = sqrt(u1);
    float2 c = unit_circle(u2);
    float t1 = r * c.x, t2 = r * c.y;
    float s = 0.5f * (1.0f + vh.z);
    t2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - t1 * t1)) + s * t2;
    float3 nh = t1 * T1 + t2 * T2 + sqrt(fmax(0.0f, 1.0f - t1 * t1 - t2 * t2)) * vh;
    return normalize((float3)(ax * nh.x, ay * nh.y, fmax(1e-6f, nh.z)));
}

/* A microfacet normal h sampled by the visible normals seen from wo (Heitz 2018, listing 1:
 * stretch, sample the projected hemisphere, unstretch); its density over wi = reflect(wo, h)
 * is ggx_pdf. */
float3 ggx_sample_h(float3 n, float3 wo, float alpha, float u1, float u2) {
    float3 t, b;
    make_frame(n, &t, &b);
    float3 hl = ggx_sample_h_aniso((float3)(dot(wo, t), dot(wo, b), dot(wo, n)), alpha, alpha, u1, u2);
    return t * hl.x + b * hl.y + n * hl.z;
}

/* Samples wi by the visible normals seen from wo. Returns the weight f cos_i / pdf =
 * F G2 / G1(wo), zero when wi falls below the surface. */
float3 ggx_sample(float3 n, float3 wo, float3 f0, float alpha, float u1, float u2, float3* wi) {
    float3 h = ggx_sample_h(n, wo, alpha, u1, u2);
    *wi = normalize(2.0f * dot(wo, h) * h - wo);
    float cos_i = dot(n, *wi), cos_o = dot(n, wo);
    if (cos_i <= 0.0f || cos_o <= 0.0f) return (float3)(0.0f);
    return fresnel_schlick(f0, dot(*wi, h)) * (ggx_g2(cos_o, cos_i, alpha) / ggx_g1(cos_o, alpha));
}

/* ---- anisotropic GGX (KHR_materials_anisotropy), in the local frame (t, b, n) of the lobe:
 * alpha_x along t, alpha_y along b (Heitz 2014, Eqs. 80 and 86; Heitz 2018 for the sampling). */

/* D(h) for h in the local frame (h.z = n.h > 0). */
float ggx_d_aniso(float3 h, float ax, float ay) {
    float x = h.x / ax, y = h.y / ay, t = x * x + y * y + h.z * h.z;
    return 1.0f / (PI_F * ax * ay * t * t);
}

/* Smith's Lambda for direction v in the local frame. */
float ggx_lambda_aniso(float3 v, float ax, float ay) {
    float z2 = fmax(v.z * v.z, 1e-12f);
    return 0.5f * (-1.0f + sqrt(1.0f + (ax * ax * v.x * v.x + ay * ay * v.y * v.y) / z2));
}

/* D G2 / (4 cos_o cos_i): the GGX reflection lobe without its Fresnel factor, which the caller
 * takes at *cos_d = wi.h. Zero below the surface. */
float ggx_reflection(float3 n, float3 wo, float3 wi, float alpha, float* cos_d) {
    float cos_o = dot(n, wo), cos_i = dot(n, wi);
    *cos_d = 1.0f;
    if (cos_o <= 0.0f || cos_i <= 0.0f) return 0.0f;
    float3 h = normalize(wo + wi);
    *cos_d = clamp(dot(wi, h), 0.0f, 1.0f);
    return ggx_d(dot(n, h), alpha) * ggx_g2(cos_o, cos_i, alpha) / (4.0f * cos_o * cos_i);
}

#endif
