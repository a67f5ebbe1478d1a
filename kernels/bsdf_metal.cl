/* bsdf_metal.cl: the Bsdf's conductor, GGX with Schlick's Fresnel from the base colour (or the
 * iridescent film's), and the multiple scattering that gives back the energy single-scattering
 * GGX loses: Kulla and Conty 2017's term for an isotropic lobe; for a stretched lobe (kernels/
 * ggx_aniso_albedo.h) mostly the lobe itself reweighted, so that what scatters twice or more
 * leaves where the grooves send it, as Heitz et al. 2016's random walk on the microsurface does. */
#ifndef CLPPM_BSDF_METAL_CL
#define CLPPM_BSDF_METAL_CL

#include "bsdf_microfacet.cl"
#include "iridescence.cl"
#include "ggx_aniso_albedo.h"

float3 metal_fresnel(const Bsdf* b, float cos_d) {
    float3 F = b->base + (1.0f - b->base) * pow5(1.0f - cos_d);
    if (!has_irid(b)) return F;
    return F + (irid_fresnel(b->irid_ior, b->irid_d, cos_d, b->base) - F) * b->irid;
}

/* Kulla-Conty multiple scattering for the conductor: F_ms (1 - A(mu_o))(1 - A(mu_i)) / (pi (1 -
 * A_avg)), F_ms = F_avg^2 A_avg / (1 - F_avg (1 - A_avg)), F_avg = F0 + (1 - F0) / 21. */
float3 metal_ms_color(const Bsdf* b, float a_avg) {
    float3 f_avg = b->base + (1.0f - b->base) * (1.0f / 21.0f);
    float3 c = f_avg * f_avg * a_avg / (1.0f - f_avg * (1.0f - a_avg));
    if (!has_irid(b)) return c;
    /* The film's part: its Fresnel at cos 0.456, where Schlick's (1 - x)^5 is its mean 1/21. Any
     * F_avg up to 1 keeps the sum of both terms at most 1. */
    float3 g = fmin(irid_fresnel(b->irid_ior, b->irid_d, 0.456f, b->base), (float3)(1.0f));
    return c + (g * g * a_avg / (1.0f - g * (1.0f - a_avg)) - c) * b->irid;
}

/* The stretched lobe's fractional indices in kernels/ggx_aniso_albedo.h: alpha (across) by
 * roughness, the stretch t = (alpha_t - alpha) / (1 - alpha). */
float aniso_row(const Bsdf* b) {
    return clamp(sqrt(b->alpha) * (float)(GGX_ANISO_ALPHA - 1), 0.0f, (float)(GGX_ANISO_ALPHA - 1));
}
float aniso_stretch(const Bsdf* b) {
    float t = b->alpha < 1.0f ? (b->alpha_t - b->alpha) / (1.0f - b->alpha) : 0.0f;
    return clamp(t * (float)(GGX_ANISO_T - 1), 0.0f, (float)(GGX_ANISO_T - 1));
}

/* A table of kernels/ggx_aniso_albedo.h at v: multilinear over (cos, azimuth from ta, alpha,
 * stretch). */
float aniso_table(const Bsdf* b, __constant const float* table, float3 v) {
    float3 l = mf_local(b, v);
    float x = sqrt(clamp(l.z, 0.0f, 1.0f)) * (float)(GGX_ANISO_MU - 1); /* rows dense at grazing */
    float y = atan2(fabs(l.y), fabs(l.x)) * (2.0f * INV_PI_F) * (float)(GGX_ANISO_PHI - 1);
    y = clamp(y, 0.0f, (float)(GGX_ANISO_PHI - 1));
    float z = aniso_row(b), w = aniso_stretch(b);
    int i = min((int)x, GGX_ANISO_MU - 2), j = min((int)y, GGX_ANISO_PHI - 2);
    int k = min((int)z, GGX_ANISO_ALPHA - 2), m = min((int)w, GGX_ANISO_T - 2);
    float fx = x - (float)i, fy = y - (float)j, fz = z - (float)k, fw = w - (float)m;
    float e = 0.0f;
    for (int c = 0; c < 16; ++c) {
        int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1, dm = (c >> 3) & 1;
        float wt = (di ? fx : 1.0f - fx) * (dj ? fy : 1.0f - fy) * (dk ? fz : 1.0f - fz) * (dm ? fw : 1.0f - fw);
        e += wt * table[(((m + dm) * GGX_ANISO_ALPHA + k + dk) * GGX_ANISO_PHI + j + dj) * GGX_ANISO_MU + i + di];
    }
    return e;
}

/* E(v) of the stretched metal lobe (F = 1), from above: the table holds an upper bound of the
 * albedo. */
float aniso_albedo(const Bsdf* b, float3 v) { return fmin(aniso_table(b, ggx_aniso_albedo, v), 1.0f); }

/* The share of a stretched lobe's multiple scattering that leaves as the lobe does: 1 - alpha /
 * alpha_t, from 0 for a round lobe (Kulla-Conty's broad term, right there) to 1 for a line. */
float aniso_lobe_share(const Bsdf* b) { return 1.0f - b->alpha / fmax(b->alpha_t, b->alpha); }

/* The cosine-weighted mean of that bound over the hemisphere. */
float aniso_albedo_avg(const Bsdf* b) {
    return table_bilinear(ggx_aniso_albedo_avg, GGX_ANISO_ALPHA, GGX_ANISO_T, aniso_row(b), aniso_stretch(b));
}

/* g: the white single-scattering lobe at (wo, wi), D G2 / (4 cos_o cos_i) (mf_reflection). */
float3 metal_ms_eval(const Bsdf* b, float3 wo, float3 wi, float cos_o, float cos_i, float al_o, float al_i, float g) {
    /* A stretched lobe: Kulla-Conty on the upper bound of its albedo, and the lobe reweighted,
     * F_ms k(wo) k(wi) g, with k from kernels/ggx_aniso_albedo.h so that each gives back what the
     * lobe loses, a little less, never more; aniso_lobe_share splits between them. Both are
     * reciprocal. */
    if (has_aniso(b)) {
        float a_avg = aniso_albedo_avg(b);
        if (!(1.0f - a_avg > 1e-6f)) return (float3)(0.0f);
        float share = aniso_lobe_share(b);
        float broad = (1.0f - aniso_albedo(b, wo)) * (1.0f - aniso_albedo(b, wi)) * INV_PI_F / (1.0f - a_avg);
        float lobe = aniso_table(b, ggx_aniso_ms_scale, wo) * aniso_table(b, ggx_aniso_ms_scale, wi) * g;
        return metal_ms_color(b, a_avg) * (b->metal * ((1.0f - share) * broad + share * lobe));
    }
    float a_avg = ggx_avg(b, ggx_albedo_a_avg);
    if (!(1.0f - a_avg > 1e-6f)) return (float3)(0.0f);
    float s = (1.0f - ggx_table(ggx_albedo_a, cos_o, al_o)) * (1.0f - ggx_table(ggx_albedo_a, cos_i, al_i));
    return metal_ms_color(b, a_avg) * (b->metal * s * INV_PI_F / (1.0f - a_avg));
}

#endif
