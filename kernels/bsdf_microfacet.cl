/* bsdf_microfacet.cl: the GGX distribution of the Bsdf's reflection lobes (the specular layer,
 * the metal, the glass), isotropic or stretched along ta by KHR_materials_anisotropy (Heitz 2014's
 * anisotropic D and Smith Lambda, sampled by visible normals; kernels/ggx.cl has both), and the
 * mirror they become below MIRROR_ALPHA. */
#ifndef CLPPM_BSDF_MICROFACET_CL
#define CLPPM_BSDF_MICROFACET_CL

#include "bsdf_types.cl"
#include "fresnel.cl"
#include "ggx.cl"
#include "albedo_table.cl"

/* Mirror direction of wo about the shading normal, falling back to the geometric normal when the
 * shading normal would send the ray below the surface. */
float3 bsdf_mirror(const Bsdf* b, float3 wo) {
    float3 r = reflect_dir(-wo, b->ns);
    if (dot(r, b->ng) <= 0.0f) r = reflect_dir(-wo, b->ng);
    return r;
}

float3 mf_local(const Bsdf* b, float3 v) {
    float3 bt = cross(b->ns, b->ta);
    return (float3)(dot(v, b->ta), dot(v, bt), dot(v, b->ns));
}

/* The alpha at which the isotropic albedo tables stand for the lobe seen along v. For an
 * anisotropic lobe, the smaller one (across ta): a lobe stretched further loses more to masking, so
 * the tables then overstate its albedo, and the coupled diffuse and Kulla-Conty terms, which give
 * back what the tables say is lost, lose energy rather than gain it. (The projected alpha in v's
 * azimuth, the alpha Smith's Lambda has there, gained up to 19% on a white metal of alpha 0.8 by
 * 0.01: it understates the albedo of a lobe rough in one direction only.) */
float dir_alpha(const Bsdf* b, float3 v) { return b->alpha; }

/* D(h), h on the side of ns. */
float mf_d(const Bsdf* b, float3 h) {
    return has_aniso(b) ? ggx_d_aniso(mf_local(b, h), b->alpha_t, b->alpha) : ggx_d(dot(b->ns, h), b->alpha);
}

float mf_g1(const Bsdf* b, float3 v) {
    return has_aniso(b) ? 1.0f / (1.0f + ggx_lambda_aniso(mf_local(b, v), b->alpha_t, b->alpha))
                        : ggx_g1(dot(b->ns, v), b->alpha);
}

/* G2(wo, wi), wi on either side. */
float mf_g2(const Bsdf* b, float3 wo, float3 wi) {
    if (!has_aniso(b)) return ggx_g2(dot(b->ns, wo), fabs(dot(b->ns, wi)), b->alpha);
    return 1.0f / (1.0f + ggx_lambda_aniso(mf_local(b, wo), b->alpha_t, b->alpha) +
                   ggx_lambda_aniso(mf_local(b, wi), b->alpha_t, b->alpha));
}

/* A microfacet normal by the visible normals from wo. */
float3 mf_sample_h(const Bsdf* b, float3 wo, float u1, float u2) {
    if (!has_aniso(b)) return ggx_sample_h(b->ns, wo, b->alpha, u1, u2);
    float3 h = ggx_sample_h_aniso(mf_local(b, wo), b->alpha_t, b->alpha, u1, u2);
    return b->ta * h.x + cross(b->ns, b->ta) * h.y + b->ns * h.z;
}

/* D G2 / (4 cos_o cos_i) and *cos_d = wi.h; zero below the surface (ggx_reflection). */
float mf_reflection(const Bsdf* b, float3 wo, float3 wi, float* cos_d) {
    if (!has_aniso(b)) return ggx_reflection(b->ns, wo, wi, b->alpha, cos_d);
    float cos_o = dot(b->ns, wo), cos_i = dot(b->ns, wi);
    *cos_d = 1.0f;
    if (cos_o <= 0.0f || cos_i <= 0.0f) return 0.0f;
    float3 h = normalize(wo + wi);
    *cos_d = clamp(dot(wi, h), 0.0f, 1.0f);
    return mf_d(b, h) * mf_g2(b, wo, wi) / (4.0f * cos_o * cos_i);
}

/* The density of mf_sample_h's reflection: G1(wo) D(h) / (4 cos_o) (ggx_pdf). */
float mf_pdf(const Bsdf* b, float3 wo, float3 wi) {
    if (!has_aniso(b)) return ggx_pdf(b->ns, wo, wi, b->alpha);
    float cos_o = dot(b->ns, wo), cos_i = dot(b->ns, wi);
    if (cos_o <= 0.0f || cos_i <= 0.0f) return 0.0f;
    return mf_g1(b, wo) * mf_d(b, normalize(wo + wi)) / (4.0f * cos_o);
}

/* A table's hemispherical mean for the lobe, at the alpha dir_alpha gives (the cosine-weighted
 * mean of its directional values, so that the coupled terms integrate as they should). */
float ggx_avg(const Bsdf* b, __constant float* t) { return ggx_table_avg(t, b->alpha); }

#endif
