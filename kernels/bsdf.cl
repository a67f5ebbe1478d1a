/* bsdf.cl: the one scattering interface of clppm's material model, glTF 2.0's metallic-roughness
 * BRDF (Appendix B) as a physically based renderer reads it (the glTF mapping is in docs/scenes.md).
 * The eye pass, photon tracing, the gather, direct lighting and the path tracer all call it:
 * surface_bsdf() resolves a material at a hit into a Bsdf; bsdf_eval, bsdf_pdf and bsdf_sample
 * evaluate, give the density of and sample it over any set of lobes; bsdf_gathered_lobes is the
 * eye pass's rule for where hit points go. tests/bsdf_model_test.cpp holds the host reference.
 * This file combines the lobes: each family lives in its own file, bsdf_types.cl (the Bsdf and which
 * lobes it has), bsdf_microfacet.cl (GGX, isotropic or stretched), bsdf_dielectric.cl (specular
 * layer, coupled diffuse, diffuse transmission, the film), bsdf_glass.cl, bsdf_metal.cl,
 * bsdf_top_layers.cl (sheen and coat) and surface_bsdf.cl (a material at a hit).
 *
 * Lobes, with weights that sum to at most 1 (their albedos each at most 1, so no energy gain):
 *  - LOBE_METAL, weight metallic: a GGX conductor, Schlick's Fresnel with F0 = base colour, plus
 *    the multiple-scattering term of Kulla and Conty 2017 (Eq. "f_ms") that gives back the energy
 *    single-scattering GGX loses at high roughness (a white metal is white at any roughness).
 *  - the dielectric base, weight (1 - metallic)(1 - transmission):
 *    LOBE_SPECULAR, a GGX layer with Schlick's Fresnel F = F0 + (F90 - F0)(1 - wo.h)^5, F0 from
 *    KHR_materials_ior and KHR_materials_specular, and under it LOBE_DIFFUSE, Lambertian with the
 *    base colour, scaled by (1 - E(cos_o))(1 - E(cos_i)) / (1 - E_avg), where E is the layer's
 *    directional albedo (kernels/ggx_albedo.h). That scaling keeps the pair reciprocal and makes
 *    its albedo exactly E(cos_o) + base (1 - E(cos_o)) (Kelemen and Szirmay-Kalos 2001).
 *  - LOBE_GLASS, weight (1 - metallic) transmission: a dielectric interface with exact Fresnel,
 *    the transmitted light tinted by the base colour. Smooth (alpha below MIRROR_ALPHA) it is a
 *    delta pair, mirror and refraction by the ior; rough, it is the GGX dielectric of Walter et
 *    al. 2007 (reflection Eq. 20, transmission Eq. 21 with the generalised half vector, Eq. 16),
 *    sampled by visible normals and then reflect-or-refract by F(wo.h). A thin-walled material
 *    (glTF without KHR_materials_volume, or thicknessFactor 0) does not bend light: its
 *    transmission is the reflection lobe mirrored through the surface (-wo when smooth).
 *    The transmission is written in flux form: f(wo, wi) carries eta_i^2 of wi's side, so a
 *    sample's weight is (1 - F) G2 / G1 whichever way light goes and photons and eye paths share
 *    one function; eye paths thereby carry radiance times (eta_light / eta_eye)^2, which is 1
 *    whenever the camera and the lights are both outside every dielectric (docs/scenes.md).
 *  - LOBE_SHEEN, KHR_materials_sheen: sheen colour times the Charlie distribution and its
 *    visibility (Estevez and Kulla 2017, the extension's pair), D V / max(1, E_s(wo), E_s(wi)),
 *    over the lobes above, which it scales by min(1 - max(sheen) E'(wo), 1 - max(sheen) E'(wi)),
 *    E_s the lobe's directional albedo (kernels/sheen_albedo.h) and E' = min(E_s, 1): the
 *    extension's albedo scaling, with the lobe kept from exceeding albedo 1 at grazing angles
 *    (where the fit of Lambda lets the smoothest lobes reach 2.2) so that there is no gain.
 *    Sampled by the cosine.
 *  - KHR_materials_diffuse_transmission: LOBE_DIFFUSE covers both sides. A part dt of it is
 *    turned to the other side, diffuse_btdf = dt dt_colour / pi for wi below the surface, the rest
 *    (1 - dt) base / pi above (the extension's mix); both carry the layer's coupling at |cos_i|,
 *    (1 - E(|cos_o|))(1 - E(|cos_i|)) / (1 - E_avg), so the pair stays reciprocal and the albedo at
 *    wo is ((1 - dt) base + dt dt_colour)(1 - E(cos_o)). Sampled by the cosine about -ns with
 *    its own selection weight. The hit point gathers photons from either side (gather_faces).
 *  - KHR_materials_anisotropy: the GGX lobes of the layer, the metal and the glass stretch to
 *    alpha_t = alpha + (1 - alpha) s^2 along the direction ta (s the strength), alpha across it
 *    (the extension's mapping; Heitz 2014's anisotropic D and Smith Lambda, sampled by visible
 *    normals); the coupled diffuse reads the albedo tables at the smaller alpha, and a stretched
 *    metal's multiple scattering takes its albedo from kernels/ggx_aniso_albedo.h, an upper
 *    bound over (cos, azimuth, alpha, stretch), and leaves mostly as the lobe does (the share
 *    1 - alpha / alpha_t; a groove's light stays in its plane), sampled with it (metal_ms_eval).
 *  - KHR_materials_iridescence: a thin film of weight irid on the specular layer and the metal,
 *    whose Fresnel becomes (1 - irid) Schlick + irid F_film (kernels/iridescence.cl; for the
 *    layer F_film over the layer's F0, times its F90). Under the film the diffuse lobe is scaled,
 *    channel by channel, by min(1 - E_f(wo), 1 - E_f(wi)), E_f(mu) = F_film(mu) A(mu), A the GGX
 *    lobe's own albedo: so the whole is a mix by irid of two models that keep energy (exactly
 *    for a smooth layer, measured for rough ones: BsdfModel.WhiteFurnaceWithoutGain).
 *  - LOBE_COAT, KHR_materials_clearcoat: a GGX layer of weight coat (clearcoatFactor), its own alpha
 *    and normal nc, Schlick's Fresnel with F0 0.04 (ior 1.5) and F90 1, over all of the above,
 *    which it scales by min(1 - coat E_c(|nc.wo|), 1 - coat E_c(|nc.wi|)), E_c the coat's
 *    directional albedo: the rule the sheen extension gives for the layers under sheen. It is
 *    reciprocal and never gains energy (the albedo at wo is at most coat E_c(wo) + (1 - coat
 *    E_c(wo)) times the rest's); what it loses against an exact layer is light the coat would
 *    send back down into the base and the base up again (docs/scenes.md, "Materials").
 * Reflection lobes with alpha below MIRROR_ALPHA are mirrors (delta lobes): the same Fresnel at
 * the view angle, so the model is continuous in roughness down to 0.
 * All directions point away from the surface; wo is on the side of the shading normal. */
#ifndef CLPPM_BSDF_CL
#define CLPPM_BSDF_CL

/* The lobes, each in its own file; this file combines them. */
#include "bsdf_types.cl"
#include "bsdf_microfacet.cl"
#include "bsdf_top_layers.cl"
#include "bsdf_dielectric.cl"
#include "bsdf_glass.cl"
#include "bsdf_metal.cl"
#include "surface_bsdf.cl"

/* Nothing but the Lambertian lobe (no layer, metal or glass): the fast paths below. */
bool bsdf_plain_lambert(const Bsdf* b) {
    if (has_coat(b) || has_sheen(b) || has_translucent(b)) return false;
    if (HAS_METAL && b->metal > 0.0f) return false;
    if (HAS_GLASS && b->glass > 0.0f) return false;
    return !has_layer(b);
}

/* Selection weights of the five sampling techniques (diffuse, layer, glass, metal, metal's
 * multiple scattering) for the lobes in mask: estimates of each one's albedo at cos_o. Named
 * fields rather than an array: an indexed private array would live in memory on PoCL. */
#define TECH_DIFFUSE 0
#define TECH_LAYER 1
#define TECH_GLASS 2
#define TECH_METAL 3
#define TECH_METAL_MS 4
#define TECH_COAT 5
#define TECH_SHEEN 6
#define TECH_TRANSLUCENT 7

typedef struct {
    float diffuse, layer, glass, metal, metal_ms, coat, sheen, translucent, total;
} LobeWeights;

/* Scales the weights of the lobes under a layer (the sheen's too: the coat lies over it). */
void lobe_weights_under(LobeWeights* w, float rest) {
    w->diffuse *= rest;
    w->translucent *= rest;
    w->layer *= rest;
    w->glass *= rest;
    w->metal *= rest;
    w->metal_ms *= rest;
    w->sheen *= rest;
}

LobeWeights lobe_weights(const Bsdf* b, float3 wo, uint mask) {
    float cos_o = dot(b->ns, wo);
    LobeWeights w;
    w.diffuse = w.layer = w.glass = w.metal = w.metal_ms = w.coat = w.sheen = w.translucent = 0.0f;
    float al_o = dir_alpha(b, wo);
    float3 e = has_layer(b) ? layer_albedo(b, cos_o, al_o) : (float3)(0.0f);
    if (mask & LOBE_DIFFUSE) w.diffuse = b->dielectric * mean3(diffuse_reflect_color(b) * (1.0f - e));
    if (has_translucent(b) && (mask & LOBE_DIFFUSE)) w.translucent = b->dielectric * mean3(b->translucent * (1.0f - e));
    if (HAS_SPECULAR_LAYER && (mask & LOBE_SPECULAR)) w.layer = b->dielectric * mean3(e);
    if (HAS_GLASS && (mask & LOBE_GLASS)) w.glass = b->glass;
    if (HAS_METAL && (mask & LOBE_METAL) && b->metal > 0.0f) {
        bool mirror = bsdf_is_mirror(b);
        float a_o = mirror ? 1.0f : ggx_table(ggx_albedo_a, cos_o, al_o);
        w.metal = b->metal * mean3(metal_fresnel(b, cos_o)) * a_o;
        if (!mirror && has_aniso(b)) { /* the lobe-shaped share of the multiple scattering: the lobe's technique */
            float a_avg = aniso_albedo_avg(b);
            if (1.0f - a_avg > 1e-6f) {
                float ms = b->metal * mean3(metal_ms_color(b, a_avg)) * (1.0f - aniso_albedo(b, wo));
                float share = aniso_lobe_share(b);
                w.metal += ms * share;
                w.metal_ms = ms * (1.0f - share);
            }
        } else if (!mirror) {
            float a_avg = ggx_avg(b, ggx_albedo_a_avg);
            if (1.0f - a_avg > 1e-6f) w.metal_ms = b->metal * mean3(metal_ms_color(b, a_avg)) * (1.0f - a_o);
        }
    }
    if (has_sheen(b)) { /* the sheen's albedo at wo, and what it leaves of the rest */
        float e = max3(b->sheen) * fmin(1.0f, sheen_albedo_at(b, cos_o));
        lobe_weights_under(&w, 1.0f - e);
        if (mask & LOBE_SHEEN) w.sheen = e;
    }
    if (has_coat(b)) { /* the coat's albedo at wo, and what it leaves of the rest */
        float e = b->coat * coat_albedo(b, dot(b->nc, wo));
        lobe_weights_under(&w, 1.0f - e);
        if (mask & LOBE_COAT) w.coat = e;
    }
    w.total = w.diffuse + w.layer + w.glass + w.metal + w.metal_ms + w.coat + w.sheen + w.translucent;
    return w;
}

/* Whether wi lies on the same side of the smooth normal nl as of the shading normal. A normal map
 * tilts the shading normal but not the surface: light arriving from below the smooth surface (the
 * interpolated normal, past the terminator of a low-poly mesh) does not reach the point, however
 * the map tilts it, and no sampled ray leaves that way, as Blender's Cycles renders normal maps
 * (docs/scenes.md, "Materials"). Always true without a normal map (nl = ns). */
bool bsdf_smooth_side(const Bsdf* b, float3 wi) {
    return !HAS_NORMAL_MAPS || (dot(wi, b->nl) > 0.0f) == (dot(wi, b->ns) > 0.0f);
}

/* f(wo, wi) of the non-delta part of the lobes under the coat in mask. */
float3 bsdf_eval_under(const Bsdf* b, float3 wo, float3 wi, uint mask) {
    float cos_o = dot(b->ns, wo), cos_i = dot(b->ns, wi);
    float3 f = (float3)(0.0f);
    if (HAS_ROUGH_GLASS && (mask & LOBE_GLASS) && b->glass > 0.0f && glass_is_rough(b)) {
        float pdf;
        f = glass_eval(b, wo, wi, &pdf) * b->glass;
    }
    if (has_translucent(b) && (mask & LOBE_DIFFUSE) && cos_o > 0.0f && cos_i < 0.0f)
        return f + diffuse_lobe_eval(b, b->translucent, cos_o, -cos_i, dir_alpha(b, wo), dir_alpha(b, wi));
    if (cos_o <= 0.0f || cos_i <= 0.0f) return f;
    if (bsdf_plain_lambert(b)) return (mask & LOBE_DIFFUSE) ? b->base * (b->dielectric * INV_PI_F) : (float3)(0.0f);
    if (mask & LOBE_DIFFUSE) f += diffuse_eval(b, cos_o, cos_i, dir_alpha(b, wo), dir_alpha(b, wi));
    if (!HAS_NON_DIFFUSE || bsdf_is_mirror(b)) return f;
    bool layer = has_layer(b) && (mask & LOBE_SPECULAR);
    bool metal = HAS_METAL && b->metal > 0.0f && (mask & LOBE_METAL);
    if (layer || metal) {
        float cos_d;
        float g = mf_reflection(b, wo, wi, &cos_d);
        float s5 = pow5(1.0f - cos_d);
        if (!has_irid(b)) {
            if (layer) f += (b->f0 + (b->f90 - b->f0) * s5) * (b->dielectric * g);
            if (metal)
                f += (b->base + (1.0f - b->base) * s5) * (b->metal * g) +
                     metal_ms_eval(b, wo, wi, cos_o, cos_i, dir_alpha(b, wo), dir_alpha(b, wi), g);
        } else {
            if (layer) f += layer_fresnel(b, cos_d) * (b->dielectric * g);
            if (metal)
                f += metal_fresnel(b, cos_d) * (b->metal * g) +
                     metal_ms_eval(b, wo, wi, cos_o, cos_i, dir_alpha(b, wo), dir_alpha(b, wi), g);
        }
    }
    return f;
}

/* f(wo, wi) of the non-delta part of the lobes in mask; zero for wi below the surface. */
float3 bsdf_eval(const Bsdf* b, float3 wo, float3 wi, uint mask) {
    if (!bsdf_smooth_side(b, wi)) return (float3)(0.0f);
    float3 f = bsdf_eval_under(b, wo, wi, mask);
    if (has_sheen(b)) {
        f *= sheen_scale(b, wo, wi);
        if ((mask & LOBE_SHEEN) && dot(b->ns, wi) > 0.0f) f += sheen_eval(b, wo, wi);
    }
    if (!has_coat(b)) return f;
    f *= coat_scale(b, wo, wi);
    if ((mask & LOBE_COAT) && !coat_is_mirror(b) && dot(b->ns, wi) > 0.0f) {
        float cos_d;
        float g = ggx_reflection(b->nc, wo, wi, b->coat_alpha, &cos_d);
        f += b->coat * (COAT_F0 + (1.0f - COAT_F0) * pow5(1.0f - cos_d)) * g;
    }
    return f;
}

/* The density bsdf_sample draws a non-delta wi with, given the selection weights w. */
float bsdf_pdf_weighted(const Bsdf* b, float3 wo, float3 wi, const LobeWeights* w) {
    if (!bsdf_smooth_side(b, wi)) return 0.0f;
    float cos_o = dot(b->ns, wo), cos_i = dot(b->ns, wi);
    if (cos_o <= 0.0f || !(w->total > 0.0f)) return 0.0f;
    float p = 0.0f;
    if (HAS_ROUGH_GLASS && w->glass > 0.0f && glass_is_rough(b)) {
        glass_eval(b, wo, wi, &p);
        p *= w->glass;
    }
    if (cos_i < 0.0f && w->translucent > 0.0f) p += w->translucent * -cos_i * INV_PI_F;
    if (cos_i <= 0.0f) return p / w->total;
    if (w->coat > 0.0f && !coat_is_mirror(b)) p += w->coat * ggx_pdf(b->nc, wo, wi, b->coat_alpha);
    p += (w->diffuse + w->metal_ms + w->sheen) * cos_i * INV_PI_F;
    if (!bsdf_is_mirror(b) && w->layer + w->metal > 0.0f) p += (w->layer + w->metal) * mf_pdf(b, wo, wi);
    return p / w->total;
}

float bsdf_pdf(const Bsdf* b, float3 wo, float3 wi, uint mask) {
    if (bsdf_plain_lambert(b)) {
        float cos_i = dot(b->ns, wi);
        return (mask & LOBE_DIFFUSE) && dot(b->ns, wo) > 0.0f && cos_i > 0.0f && bsdf_smooth_side(b, wi)
                   ? cos_i * INV_PI_F
                   : 0.0f;
    }
    LobeWeights w = lobe_weights(b, wo, mask);
    return bsdf_pdf_weighted(b, wo, wi, &w);
}

/* A plain Lambertian surface: f cos / pdf is the albedo itself, no lobe to choose. */
bool sample_plain_lambert(const Bsdf* b, uint mask, float u1, float u2, BsdfSample* s) {
    if (!(mask & LOBE_DIFFUSE) || !(b->dielectric > 0.0f)) return false;
    s->wi = sample_cosine_hemisphere(b->ns, u1, u2);
    float cos_i = dot(b->ns, s->wi);
    if (cos_i <= 0.0f || dot(s->wi, b->ng) <= 0.0f) return false;
    s->pdf = cos_i * INV_PI_F;
    s->weight = b->base * b->dielectric;
    return true;
}

/* The technique u_lobe picks: the last one with weight whose cumulative range holds
 * u_lobe w->total. Its weight goes to *wt, and u_lobe rescaled to [0, 1) within it to *u_in (glass's
 * reflect-or-refract choice). */
int lobe_technique(const LobeWeights* w, float u_lobe, float* wt, float* u_in) {
    float u = u_lobe * w->total, acc = 0.0f;
    int tech = -1;
    bool found = false;
    *wt = 0.0f;
#define CLPPM_PICK(field, id)                                                                                          \
    if (!found && w->field > 0.0f) {                                                                                   \
        tech = id;                                                                                                     \
        *wt = w->field;                                                                                                \
        if (u < acc + w->field) found = true;                                                                          \
        else acc += w->field;                                                                                          \
    }
    CLPPM_PICK(diffuse, TECH_DIFFUSE)
    CLPPM_PICK(layer, TECH_LAYER)
    CLPPM_PICK(glass, TECH_GLASS)
    CLPPM_PICK(metal, TECH_METAL)
    CLPPM_PICK(metal_ms, TECH_METAL_MS)
    CLPPM_PICK(coat, TECH_COAT)
    CLPPM_PICK(sheen, TECH_SHEEN)
    CLPPM_PICK(translucent, TECH_TRANSLUCENT)
#undef CLPPM_PICK
    if (!found) acc -= *wt; /* u rounded past the end: the last technique */
    *u_in = clamp((u - acc) / *wt, 0.0f, 0.99999994f);
    return tech;
}

/* Whether the technique samples a delta lobe here: smooth glass, a mirror layer or metal, a
 * smooth coat. */
bool technique_is_delta(const Bsdf* b, int tech) {
    if (HAS_GLASS && tech == TECH_GLASS) return !glass_is_rough(b);
    if (tech == TECH_LAYER || tech == TECH_METAL) return bsdf_is_mirror(b);
    return tech == TECH_COAT && coat_is_mirror(b);
}

/* A delta technique's direction and its coefficient over p_tech, the probability of choosing it. */
bool sample_delta(const Bsdf* b, float3 wo, int tech, float u_in, float p_tech, BsdfSample* s) {
    float cos_o = dot(b->ns, wo);
    s->delta = true;
    if (HAS_GLASS && tech == TECH_GLASS) {
        /* Reflect with probability F: the Fresnel weights cancel the probabilities. */
        float F = fresnel_dielectric(cos_o, b->eta);
        if (u_in < F) {
            s->wi = bsdf_mirror(b, wo);
            s->weight = (float3)(b->glass * layers_scale(b, wo, s->wi) / p_tech);
            return true;
        }
        s->wi = b->thin ? -wo : refract_dir(-wo, b->ns, b->eta);
        if (dot(s->wi, b->ng) >= 0.0f) return false;
        s->below = true;
        s->weight = b->base * (b->glass * layers_scale(b, wo, s->wi) * refraction_scale(b) / p_tech);
        return true;
    }
    if (tech == TECH_LAYER || tech == TECH_METAL) {
        s->wi = bsdf_mirror(b, wo);
        float3 F = tech == TECH_LAYER ? layer_fresnel(b, cos_o) * b->dielectric : metal_fresnel(b, cos_o) * b->metal;
        s->weight = F * layers_scale(b, wo, s->wi) / p_tech;
        return true;
    }
    /* A smooth coat: its mirror, Fresnel at the view. */
    s->wi = reflect_dir(-wo, b->nc);
    if (dot(s->wi, b->ng) <= 0.0f || dot(s->wi, b->ns) <= 0.0f) return false;
    float cos_c = clamp(dot(b->nc, wo), 0.0f, 1.0f);
    s->weight = (float3)(b->coat * (COAT_F0 + (1.0f - COAT_F0) * pow5(1.0f - cos_c)) / p_tech);
    return true;
}

/* A non-delta technique's direction: the cosine about ns (diffuse, the metal's multiple
 * scattering, sheen) or -ns (diffuse transmission), visible normals of the coat's or the Bsdf's
 * GGX, or the rough glass's reflection or refraction (s->below when wi leaves through the
 * surface). False when the technique gives none. */
bool sample_direction(const Bsdf* b, float3 wo, int tech, float u_in, float u1, float u2, BsdfSample* s) {
    if (HAS_GLASS && tech == TECH_GLASS) return glass_sample(b, wo, u_in, u1, u2, &s->wi, &s->below);
    if (HAS_DIFFUSE_TRANSMISSION && tech == TECH_TRANSLUCENT) {
        s->wi = sample_cosine_hemisphere(-b->ns, u1, u2);
        s->below = true;
    } else if (tech == TECH_DIFFUSE || tech == TECH_METAL_MS || tech == TECH_SHEEN) {
        s->wi = sample_cosine_hemisphere(b->ns, u1, u2);
    } else if (tech == TECH_COAT) {
        float3 h = ggx_sample_h(b->nc, wo, b->coat_alpha, u1, u2);
        s->wi = normalize(2.0f * dot(wo, h) * h - wo);
    } else {
        float3 h = mf_sample_h(b, wo, u1, u2);
        s->wi = normalize(2.0f * dot(wo, h) * h - wo);
    }
    return true;
}

/* Samples the lobes in mask: one technique chosen by its weight with u_lobe, then the direction
 * with (u1, u2). Non-delta samples are weighted by the whole set's eval and pdf (one-sample MIS
 * over the lobes). False when nothing is sampled (no lobe, or wi below the geometric surface). */
bool bsdf_sample_lobes(const Bsdf* b, float3 wo, uint mask, float u_lobe, float u1, float u2, BsdfSample* s) {
    float cos_o = dot(b->ns, wo);
    s->delta = false;
    s->below = false;
    s->pdf = 0.0f;
    s->weight = (float3)(0.0f);
    if (!(cos_o > 0.0f)) return false;
    if (bsdf_plain_lambert(b)) return sample_plain_lambert(b, mask, u1, u2, s);
    LobeWeights w = lobe_weights(b, wo, mask);
    if (!(w.total > 0.0f)) return false;
    float wt, u_in;
    int tech = lobe_technique(&w, u_lobe, &wt, &u_in);
    float p_tech = wt / w.total;
    if (technique_is_delta(b, tech)) return sample_delta(b, wo, tech, u_in, p_tech, s);
    if (!sample_direction(b, wo, tech, u_in, u1, u2, s)) return false;
    float cos_i = dot(b->ns, s->wi);
    if (s->below) { /* through the surface: only rough glass and diffuse transmission reach there */
        if (cos_i >= 0.0f || dot(s->wi, b->ng) >= 0.0f) return false;
        s->pdf = bsdf_pdf_weighted(b, wo, s->wi, &w);
        if (!(s->pdf > 0.0f)) return false;
        s->weight = bsdf_eval(b, wo, s->wi, mask) * (-cos_i / s->pdf);
        return true;
    }
    if (cos_i <= 0.0f || dot(s->wi, b->ng) <= 0.0f) return false;
    if (!HAS_NON_DIFFUSE || (!has_coat(b) && !has_sheen(b) && !has_translucent(b) &&
                             ((mask & ~LOBE_DIFFUSE) == 0u || w.total == w.diffuse))) {
        /* Only the diffuse lobe: f cos / pdf in closed form (exactly the base colour when the
         * surface is plain Lambertian). */
        s->pdf = cos_i * INV_PI_F;
        s->weight = diffuse_eval(b, cos_o, cos_i, dir_alpha(b, wo), dir_alpha(b, s->wi)) * (PI_F / p_tech);
        if (!has_layer(b)) s->weight = b->base * (b->dielectric / p_tech);
        return true;
    }
    s->pdf = bsdf_pdf_weighted(b, wo, s->wi, &w);
    if (!(s->pdf > 0.0f)) return false;
    s->weight = bsdf_eval(b, wo, s->wi, mask) * (cos_i / s->pdf);
    return true;
}
bool bsdf_sample(const Bsdf* b, float3 wo, uint mask, float u_lobe, float u1, float u2, BsdfSample* s) {
    return bsdf_sample_lobes(b, wo, mask, u_lobe, u1, u2, s) && bsdf_smooth_side(b, s->wi);
}

/* The density with which bsdf_sample, sampling from wi, draws wo (the reverse density of
 * bidirectional methods): wi through the surface (rough glass) is sampled from the other side,
 * where the normals turn over and the relative index inverts. */
float bsdf_pdf_rev(const Bsdf* b, float3 wo, float3 wi, uint mask) {
    if (dot(wi, b->ns) > 0.0f) return bsdf_pdf(b, wi, wo, mask);
    Bsdf f = *b;
    f.ns = -b->ns;
    f.ng = -b->ng;
    f.nl = -b->nl;
    f.nc = -b->nc;
    if (!b->thin) f.eta = 1.0f / b->eta;
    return bsdf_pdf(&f, wi, wo, mask);
}

/* Whether a lobe other than a delta one exists here: what a connection or a merge can evaluate. */
bool bsdf_has_nondelta(const Bsdf* b) {
    if ((has_coat(b) && !coat_is_mirror(b)) || has_sheen(b)) return true;
    if (b->dielectric > 0.0f && (max3(b->base) > 0.0f || (has_translucent(b) && max3(b->translucent) > 0.0f)))
        return true;
    if (!bsdf_is_mirror(b) && (has_layer(b) || (HAS_METAL && b->metal > 0.0f))) return true;
    return HAS_ROUGH_GLASS && b->glass > 0.0f && glass_is_rough(b);
}

/* Whether light can pass between the surface and unit direction wi for the lobes in mask: above
 * both normals, or below both through rough glass or diffuse transmission (a light sample or a
 * connection). */
bool bsdf_connects(const Bsdf* b, float3 wi, uint mask) {
    if (dot(wi, b->ns) < 0.0f) {
        bool through = (HAS_ROUGH_GLASS && (mask & LOBE_GLASS) && b->glass > 0.0f && glass_is_rough(b)) ||
                       (has_translucent(b) && (mask & LOBE_DIFFUSE) && b->dielectric > 0.0f);
        return through && dot(wi, b->ng) < 0.0f;
    }
    return dot(wi, b->ns) > 0.0f && dot(wi, b->ng) > 0.0f;
}

/* The lobes a hit point keeps (the gather and direct lighting evaluate them there): the diffuse
 * one, and the reflection lobes when they are rough enough. The eye pass follows the others. */
uint bsdf_gathered_lobes(float alpha) {
    return alpha >= GLOSSY_HITPOINT_ALPHA ? (LOBE_DIFFUSE | LOBE_SPECULAR | LOBE_METAL) : LOBE_DIFFUSE;
}

/* The same for a whole BSDF: the coat too when it is rough enough. */
uint bsdf_gathered(const Bsdf* b) {
    uint lobes = bsdf_gathered_lobes(b->alpha) | (has_sheen(b) ? LOBE_SHEEN : 0u);
    return has_coat(b) && b->coat_alpha >= GLOSSY_HITPOINT_ALPHA ? lobes | LOBE_COAT : lobes;
}

/* Whether the surface has a lobe hit points keep (photons are stored there). */
bool bsdf_has_gathered(const Bsdf* b) {
    if ((has_coat(b) && b->coat_alpha >= GLOSSY_HITPOINT_ALPHA) || has_sheen(b) || has_translucent(b)) return true;
    if (b->dielectric > 0.0f && (max3(b->base) > 0.0f || has_layer(b))) return true;
    return HAS_METAL && b->metal > 0.0f && b->alpha >= GLOSSY_HITPOINT_ALPHA;
}

#endif
