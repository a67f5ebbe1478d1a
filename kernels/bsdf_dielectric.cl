/* bsdf_dielectric.cl: the dielectric base of the Bsdf, a GGX specular layer with Schlick's
 * Fresnel (KHR_materials_ior, _specular), under it the Lambertian lobe coupled to the layer's
 * albedo (Kelemen and Szirmay-Kalos 2001), part of it turned to the other side by
 * KHR_materials_diffuse_transmission, and KHR_materials_iridescence's film on the layer
 * (kernels/bsdf.cl describes the model). */
#ifndef CLPPM_BSDF_DIELECTRIC_CL
#define CLPPM_BSDF_DIELECTRIC_CL

#include "bsdf_microfacet.cl"
#include "iridescence.cl"

/* E(mu): the dielectric layer's directional albedo (exact Schlick for a mirror). */
float3 layer_albedo(const Bsdf* b, float mu, float alpha) {
    if (bsdf_is_mirror(b)) return b->f0 + (b->f90 - b->f0) * pow5(1.0f - mu);
    return b->f0 * ggx_table(ggx_albedo_a, mu, alpha) + (b->f90 - b->f0) * ggx_table(ggx_albedo_b, mu, alpha);
}

/* E_avg = 2 int E(mu) mu dmu (Schlick's mean is F0 + (F90 - F0) / 21). */
float3 layer_albedo_avg(const Bsdf* b) {
    if (bsdf_is_mirror(b)) return b->f0 + (b->f90 - b->f0) * (1.0f / 21.0f);
    return b->f0 * ggx_avg(b, ggx_albedo_a_avg) + (b->f90 - b->f0) * ggx_avg(b, ggx_albedo_b_avg);
}

/* The diffuse reflection's colour: the base, less the part turned to the other side. */
float3 diffuse_reflect_color(const Bsdf* b) { return has_translucent(b) ? b->base * (1.0f - b->dt) : b->base; }

/* The specular layer's thin-film Fresnel: over the layer's F0 (without the specular factor),
 * times that factor (F90). */
float3 layer_film_fresnel(const Bsdf* b, float cos_d) {
    if (!(b->f90 > 0.0f)) return (float3)(0.0f);
    return b->f90 * irid_fresnel(b->irid_ior, b->irid_d, cos_d, b->f0 / b->f90);
}

/* The specular layer's Fresnel at cos_d = wi.h: Schlick's, mixed with the film's. */
float3 layer_fresnel(const Bsdf* b, float cos_d) {
    float3 F = b->f0 + (b->f90 - b->f0) * pow5(1.0f - cos_d);
    if (!has_irid(b)) return F;
    return F + (layer_film_fresnel(b, cos_d) - F) * b->irid;
}

/* E_f(mu): the filmed layer's directional albedo, estimated as A(mu) F_film(x), A the GGX lobe's
 * own albedo and x the cosine at which (1 - x)^5 is the lobe's mean of (1 - wo.h)^5, B(mu) / A(mu)
 * from the tables: the microfacets' typical angle to the view (exact for a smooth layer, x = mu). */
float3 film_layer_albedo(const Bsdf* b, float mu, float alpha) {
    if (bsdf_is_mirror(b)) return layer_film_fresnel(b, mu);
    float a = ggx_table(ggx_albedo_a, mu, alpha), bb = ggx_table(ggx_albedo_b, mu, alpha);
    float x = a > 1e-6f ? 1.0f - pow(clamp(bb / a, 0.0f, 1.0f), 0.2f) : mu;
    /* 3% over, since the estimate is no bound: measured within 1.2% of the true albedo. */
    return fmin(layer_film_fresnel(b, x) * (a * 1.03f), (float3)(1.0f));
}

/* The diffuse lobe of colour `color` (the reflection's or, with cos_i = |cos_i|, the transmission's):
 * color / pi, scaled for the layer above it; al_o and al_i the tables' alpha towards wo and wi
 * (dir_alpha). */
float3 diffuse_lobe_eval(const Bsdf* b, float3 color, float cos_o, float cos_i, float al_o, float al_i) {
    float3 c = color * (b->dielectric * INV_PI_F);
    if (!has_layer(b)) return c;
    float3 one = (float3)(1.0f);
    float3 rest = one - layer_albedo_avg(b);
    float3 s = (one - layer_albedo(b, cos_o, al_o)) * (one - layer_albedo(b, cos_i, al_i));
    float3 d = select((float3)(0.0f), c * s / rest, isgreater(rest, (float3)(1e-6f)));
    if (!has_irid(b)) return d;
    /* Under the film, channel by channel: min(1 - E_f(wo), 1 - E_f(wi)). */
    float3 e = fmax(film_layer_albedo(b, cos_o, al_o), film_layer_albedo(b, cos_i, al_i));
    return d + (c * fmax((float3)(0.0f), 1.0f - e) - d) * b->irid;
}

/* The diffuse reflection, wi above the surface. */
float3 diffuse_eval(const Bsdf* b, float cos_o, float cos_i, float al_o, float al_i) {
    return diffuse_lobe_eval(b, diffuse_reflect_color(b), cos_o, cos_i, al_o, al_i);
}

#endif
