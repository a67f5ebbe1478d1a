/* bsdf_top_layers.cl: the two layers over the rest of the Bsdf, KHR_materials_sheen's Charlie
 * lobe and KHR_materials_clearcoat's GGX coat, and what each leaves of the lobes under it: 1 minus
 * its weight times the larger of its directional albedos towards wo and wi (kernels/bsdf.cl). */
#ifndef CLPPM_BSDF_TOP_LAYERS_CL
#define CLPPM_BSDF_TOP_LAYERS_CL

#include "bsdf_types.cl"
#include "fresnel.cl"
#include "albedo_table.cl"
#include "sheen_albedo.h"

/* E_c(mu): the coat's directional albedo, F0 COAT_F0 and F90 1 (exact Schlick for a mirror). */
float coat_albedo(const Bsdf* b, float mu) {
    mu = clamp(mu, 0.0f, 1.0f);
    if (coat_is_mirror(b)) return COAT_F0 + (1.0f - COAT_F0) * pow5(1.0f - mu);
    return COAT_F0 * ggx_table(ggx_albedo_a, mu, b->coat_alpha) +
           (1.0f - COAT_F0) * ggx_table(ggx_albedo_b, mu, b->coat_alpha);
}

/* What the coat leaves of the lobes under it for light between wo and wi (either side). */
float coat_scale(const Bsdf* b, float3 wo, float3 wi) {
    if (!has_coat(b)) return 1.0f;
    float e = fmax(coat_albedo(b, fabs(dot(b->nc, wo))), coat_albedo(b, fabs(dot(b->nc, wi))));
    return fmax(0.0f, 1.0f - b->coat * e);
}

/* E_s(mu): the sheen lobe's directional albedo for colour 1 (bilinear in kernels/sheen_albedo.h,
 * its rows by roughness from SHEEN_MIN_ROUGHNESS to 1). */
float sheen_albedo_at(const Bsdf* b, float mu) {
    return table_bilinear(sheen_albedo, SHEEN_ALBEDO_MU, SHEEN_ALBEDO_R, mu * (float)SHEEN_ALBEDO_MU - 0.5f,
                          (b->sheen_r - SHEEN_MIN_ROUGHNESS) / (1.0f - SHEEN_MIN_ROUGHNESS) *
                              (float)(SHEEN_ALBEDO_R - 1));
}

/* What the sheen leaves of the lobes under it. */
float sheen_scale(const Bsdf* b, float3 wo, float3 wi) {
    if (!has_sheen(b)) return 1.0f;
    float e = fmin(1.0f, fmax(sheen_albedo_at(b, fabs(dot(b->ns, wo))), sheen_albedo_at(b, fabs(dot(b->ns, wi)))));
    return fmax(0.0f, 1.0f - max3(b->sheen) * e);
}

/* Lambda of the Charlie microfibres (Estevez and Kulla 2017, Sec. 3, their fit of ln Lambda; the
 * extension's "Sheen visibility"), for 0 < cos_t <= 1: the fit l(x) below cos 0.5, mirrored
 * about 0.5 above it (x kept at least 0 where rounding puts cos_t above 1). */
float sheen_l(float x, float alpha) {
    float t = (1.0f - alpha) * (1.0f - alpha);
    float a = mix(21.5473f, 25.3245f, t), bb = mix(3.82987f, 3.32435f, t), c = mix(0.19823f, 0.16801f, t);
    float d = mix(-1.97760f, -1.27393f, t), e = mix(-4.32054f, -4.85967f, t);
    return a / (1.0f + bb * pow(fmax(x, 0.0f), c)) + d * x + e;
}
float sheen_lambda(float cos_t, float alpha) {
    return cos_t < 0.5f ? exp(sheen_l(cos_t, alpha)) : exp(2.0f * sheen_l(0.5f, alpha) - sheen_l(1.0f - cos_t, alpha));
}

/* The sheen lobe at (wo, wi), both above ns: sheen D V, V = 1 / ((1 + Lambda(o) + Lambda(i))
 * 4 cos_o cos_i), the extension's distribution and visibility with alpha = roughness^2. */
float3 sheen_eval(const Bsdf* b, float3 wo, float3 wi) {
    float cos_o = dot(b->ns, wo), cos_i = dot(b->ns, wi);
    if (!(cos_o > 0.0f) || !(cos_i > 0.0f)) return (float3)(0.0f);
    float3 h = normalize(wo + wi);
    float ch = dot(b->ns, h), alpha = b->sheen_r * b->sheen_r;
    float d = (2.0f + 1.0f / alpha) * pow(fmax(0.0f, 1.0f - ch * ch), 0.5f / alpha) * (0.5f * INV_PI_F);
    float v = 1.0f / ((1.0f + sheen_lambda(cos_o, alpha) + sheen_lambda(cos_i, alpha)) * 4.0f * cos_o * cos_i);
    float norm = fmax(1.0f, fmax(sheen_albedo_at(b, cos_o), sheen_albedo_at(b, cos_i)));
    return b->sheen * (d * v / norm);
}

/* What the coat and the sheen leave of the lobes under both. */
float layers_scale(const Bsdf* b, float3 wo, float3 wi) { return coat_scale(b, wo, wi) * sheen_scale(b, wo, wi); }

#endif
