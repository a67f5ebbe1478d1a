/* bsdf_glass.cl: KHR_materials_transmission's glass lobe when rough, the GGX dielectric of Walter
 * et al. 2007, thin-walled or refracting (kernels/bsdf.cl describes the model; the smooth pair of
 * mirror and refraction is sampled there). */
#ifndef CLPPM_BSDF_GLASS_CL
#define CLPPM_BSDF_GLASS_CL

#include "bsdf_microfacet.cl"

/* The glass lobe is a rough dielectric (not a delta pair). An interface of index 1 does not
 * refract at any roughness: it stays a delta (straight through), where the rough lobe's
 * Jacobian would be singular. */
bool glass_is_rough(const Bsdf* b) {
    return HAS_GLASS && HAS_ROUGH_GLASS && !bsdf_is_mirror(b) && (b->thin || fabs(b->eta - 1.0f) > 1e-3f);
}

/* The rough glass lobe at (wo, wi), unweighted: f, with the transmission tinted by the base
 * colour, and in *pdf the density glass_sample draws wi with. wi below the surface is
 * transmission. Walter et al. 2007: D G2 F / (4 |cos_o cos_i|) for reflection and, for
 * refraction through h = +-normalize(wo + eta wi) (Eq. 16), (1 - F) D G2 |wo.h| |wi.h| eta^2 /
 * (|cos_o cos_i| (wo.h + eta wi.h)^2) (Eq. 21 in flux form, see above), whose last factor
 * eta^2 |wi.h| / (wo.h + eta wi.h)^2 is the Jacobian dh / dwi (Eq. 17). */
/* What refraction through the glass lobe scales a path's weight by: 1/eta^2 for radiance, 1 for
 * importance (TRANSPORT_RADIANCE above); thin walls do not bend light and scale nothing. */
float refraction_scale(const Bsdf* b) { return b->radiance && !b->thin ? 1.0f / (b->eta * b->eta) : 1.0f; }

float3 glass_eval(const Bsdf* b, float3 wo, float3 wi, float* pdf) {
    *pdf = 0.0f;
    float3 n = b->ns;
    float cos_o = dot(n, wo), cos_i = dot(n, wi);
    if (!(cos_o > 0.0f) || cos_i == 0.0f) return (float3)(0.0f);
    bool reflect = cos_i > 0.0f;
    float3 h;
    if (reflect) h = wo + wi;
    else if (b->thin) h = wo + (wi - 2.0f * cos_i * n); /* wi mirrored back above the surface */
    else h = wo + b->eta * wi;
    float hl = length(h);
    if (!(hl > 0.0f)) return (float3)(0.0f);
    h /= hl;
    if (dot(h, n) < 0.0f) h = -h;
    float o_h = dot(wo, h);
    if (!(o_h > 0.0f)) return (float3)(0.0f);
    float F = fresnel_dielectric(o_h, b->eta);
    float d = mf_d(b, h);
    float g1 = mf_g1(b, wo), g2 = mf_g2(b, wo, wi);
    if (reflect || b->thin) {
        float k = reflect ? F : 1.0f - F;
        *pdf = k * g1 * d / (4.0f * cos_o);
        float f = k * d * g2 / (4.0f * cos_o * fabs(cos_i));
        return reflect ? (float3)(f) : b->base * f;
    }
    float i_h = dot(wi, h);
    if (!(i_h < 0.0f) || !(F < 1.0f)) return (float3)(0.0f);
    float denom = o_h + b->eta * i_h;
    float jacobian = b->eta * b->eta * -i_h / (denom * denom);
    *pdf = (1.0f - F) * g1 * d * o_h / cos_o * jacobian;
    return b->base * ((1.0f - F) * d * g2 * o_h / (cos_o * -cos_i) * jacobian * refraction_scale(b));
}

/* Samples the rough glass lobe: h by the visible normals from wo, then reflection with
 * probability F(wo.h), else refraction through h (or, thin-walled, the reflection mirrored
 * through the surface). False when the direction falls on the wrong side. */
bool glass_sample(const Bsdf* b, float3 wo, float u_in, float u1, float u2, float3* wi, bool* below) {
    float3 n = b->ns;
    float3 h = mf_sample_h(b, wo, u1, u2);
    float o_h = dot(wo, h);
    if (!(o_h > 0.0f)) return false;
    float F = fresnel_dielectric(o_h, b->eta);
    float3 r = normalize(2.0f * o_h * h - wo);
    if (u_in < F) {
        *wi = r;
        *below = false;
        return dot(n, r) > 0.0f;
    }
    *below = true;
    if (b->thin) {
        float c = dot(n, r);
        *wi = r - 2.0f * c * n;
        return c > 0.0f;
    }
    *wi = refract_dir(-wo, h, b->eta);
    return dot(n, *wi) < 0.0f;
}

#endif
