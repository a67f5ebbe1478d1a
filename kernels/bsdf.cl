/* bsdf.cl: the one scattering interface of clppm's material model, glTF 2.0's metallic-roughness
 * BRDF (Appendix B) as a physically based renderer reads it (the glTF mapping is in docs/scenes.md).
 * The eye pass, photon tracing, the gather, direct lighting and the path tracer all call it:
 * surface_bsdf() resolves a material at a hit into a Bsdf; bsdf_eval, bsdf_pdf and bsdf_sample
 * evaluate, give the density of and sample it over any set of lobes; bsdf_gathered_lobes is the
 * eye pass's rule for where hit points go. tests/bsdf_model_test.cpp holds the host reference.
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
 *  - LOBE_SHEEN, KHR_materials_sheen: sheen colour times the Charlie distribution (Estevez and
 *    Kulla 2017) with Neubelt and Pettineo's visibility, D V / max(1, E_s(wo), E_s(wi)), over the
 *    lobes above, which it scales by min(1 - max(sheen) E'(wo), 1 - max(sheen) E'(wi)), E_s the
 *    lobe's directional albedo (kernels/sheen_albedo.h) and E' = min(E_s, 1): the extension's
 *    albedo scaling, with the lobe kept from exceeding albedo 1 at grazing angles (where the
 *    smoothest Charlie lobes reach 3.7) so that there is no gain. Sampled by the cosine.
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
 *    bound over (cos, azimuth, alpha, stretch) (metal_ms_eval).
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

#include "scene.cl"
#include "ggx.cl"
#include "iridescence.cl"
#include "ggx_albedo.h"
#include "ggx_aniso_albedo.h"
#include "sheen_albedo.h"

/* Reflection lobes at least this rough (GGX alpha = roughness^2) get hit points and are gathered
 * with the BSDF; smoother ones are sampled through by the eye pass, where a density estimate
 * would blur the reflection. */
#define GLOSSY_HITPOINT_ALPHA 0.04f
/* GGX alpha below this is a mirror: the lobe is a delta (roughness below 0.01). */
#define MIRROR_ALPHA 1e-4f

#define LOBE_DIFFUSE 1u
#define LOBE_SPECULAR 2u
#define LOBE_GLASS 4u
#define LOBE_METAL 8u
#define LOBE_COAT 16u
#define LOBE_SHEEN 32u
#define LOBE_ALL 63u
/* The coat's Schlick F0: ior 1.5, as KHR_materials_clearcoat fixes it. */
#define COAT_F0 0.04f

/* What a path carries (pbrt-v4's TransportMode; Veach 1997, Sec. 5.2): a camera path radiance, a
 * light path (a photon, a light sub-path) importance. The BSDF below is written for importance;
 * refraction into a medium of relative index eta compresses radiance by eta^2, so a camera path's
 * refracted light is 1/eta^2 of that. Paths that leave a solid as they entered it see both
 * factors cancel, so only a camera vertex inside a refracting solid (VCM merging and connecting at
 * rough glass) tells the two apart. */
#define TRANSPORT_RADIANCE 0u
#define TRANSPORT_IMPORTANCE 1u

typedef struct {
    float3 ns, ng;                  /* shading and geometric normal on the side of wo */
    float3 nl;                      /* the smooth normal, ns before any normal map (bsdf_smooth_side) */
    float3 base;                    /* base colour */
    float3 f0;                      /* dielectric layer: Schlick F0 */
    float f90;                      /* and F90 */
    float alpha;                    /* GGX alpha of both reflection lobes */
    float dielectric, glass, metal; /* lobe weights */
    float eta;                      /* LOBE_GLASS: relative index n_t / n_i for light crossing from the ns side */
    bool thin;                      /* LOBE_GLASS: thin-walled, transmission does not bend */
    bool radiance;                  /* carries radiance (TRANSPORT_RADIANCE): refraction scales by 1/eta^2 */
    bool front;                     /* the side of ns is outside the mesh (the winding's front) */
    float3 sigma;                   /* KHR_materials_volume: the mesh's absorption coefficient */
    float3 nc;                      /* LOBE_COAT: the coat's normal, on the side of wo */
    float coat, coat_alpha;         /* LOBE_COAT: weight (0: none) and GGX alpha */
    float3 sheen;                   /* LOBE_SHEEN: colour (0: none) */
    float sheen_r;                  /* LOBE_SHEEN: roughness, at least SHEEN_MIN_ROUGHNESS */
    float irid, irid_ior, irid_d;   /* KHR_materials_iridescence: weight (0: none), index, thickness (nm) */
    float3 ta;                      /* KHR_materials_anisotropy: the direction of alpha_t, across ns */
    float alpha_t;                  /* GGX alpha along ta; alpha (across) otherwise */
    float3 translucent;             /* KHR_materials_diffuse_transmission: dt times its colour (0: none) */
    float dt;                       /* and dt, the part of the diffuse lobe turned to the other side */
} Bsdf;

typedef struct {
    float3 wi;
    float3 weight; /* f cos / pdf; for a delta lobe its coefficient over the probability of choosing it */
    float pdf;     /* solid-angle density of wi over the sampled lobe set; 0 for a delta lobe */
    bool delta;
    bool below; /* wi leaves through the surface (refraction) */
} BsdfSample;

/* ---- Fresnel and specular directions ---------------------------------------------------------- */

/* Unpolarised Fresnel reflectance for a dielectric; cos_i > 0 on the incident side and eta the
 * relative index n_t / n_i (pbrt-v4 FrDielectric). Returns 1 under total internal reflection. */
float fresnel_dielectric(float cos_i, float eta) {
    cos_i = clamp(cos_i, 0.0f, 1.0f);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;
    float cos_t = sqrt(1.0f - sin2_t);
    float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

float3 reflect_dir(float3 d, float3 n) { return d - 2.0f * dot(d, n) * n; }

/* Refraction of incoming direction d (pointing at the surface) through normal n (facing against
 * d), relative index eta = n_t / n_i. Valid only when fresnel_dielectric < 1. */
float3 refract_dir(float3 d, float3 n, float eta) {
    float cos_i = -dot(d, n);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    return normalize(d / eta + (cos_i / eta - cos_t) * n);
}

/* Mirror direction of wo about the shading normal, falling back to the geometric normal when the
 * shading normal would send the ray below the surface. */
float3 bsdf_mirror(const Bsdf* b, float3 wo) {
    float3 r = reflect_dir(-wo, b->ns);
    if (dot(r, b->ng) <= 0.0f) r = reflect_dir(-wo, b->ng);
    return r;
}

float pow5(float x) { return (x * x) * (x * x) * x; }

float mean3(float3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

/* ---- the albedo tables ------------------------------------------------------------------------ */

/* Bilinear lookup in a GGX_ALBEDO_ALPHA x GGX_ALBEDO_MU table (kernels/ggx_albedo.h), whose rows
 * go by roughness = sqrt(alpha). */
float ggx_table(__constant float* t, float mu, float alpha) {
    float x = clamp(mu * (float)GGX_ALBEDO_MU - 0.5f, 0.0f, (float)(GGX_ALBEDO_MU - 1));
    float y = clamp(sqrt(alpha) * (float)(GGX_ALBEDO_ALPHA - 1), 0.0f, (float)(GGX_ALBEDO_ALPHA - 1));
    int i = min((int)x, GGX_ALBEDO_MU - 2), j = min((int)y, GGX_ALBEDO_ALPHA - 2);
    float fx = x - (float)i, fy = y - (float)j;
    __constant float* r0 = t + j * GGX_ALBEDO_MU;
    __constant float* r1 = r0 + GGX_ALBEDO_MU;
    float a = r0[i] + (r0[i + 1] - r0[i]) * fx, c = r1[i] + (r1[i + 1] - r1[i]) * fx;
    return a + (c - a) * fy;
}

float ggx_table_avg(__constant float* t, float alpha) {
    float y = clamp(sqrt(alpha) * (float)(GGX_ALBEDO_ALPHA - 1), 0.0f, (float)(GGX_ALBEDO_ALPHA - 1));
    int j = min((int)y, GGX_ALBEDO_ALPHA - 2);
    float fy = y - (float)j;
    return t[j] + (t[j + 1] - t[j]) * fy;
}

/* KHR_materials_anisotropy: the GGX lobes (layer, metal, glass) stretch to alpha_t along ta. */
bool has_aniso(const Bsdf* b) { return HAS_ANISOTROPY && b->alpha_t != b->alpha; }

/* A mirror only when smooth in every direction. */
bool bsdf_is_mirror(const Bsdf* b) { return (HAS_ANISOTROPY ? fmax(b->alpha, b->alpha_t) : b->alpha) < MIRROR_ALPHA; }

/* ---- the microfacet lobes' GGX, isotropic or anisotropic ---------------------------------------- */

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

bool has_coat(const Bsdf* b) { return HAS_CLEARCOAT && b->coat > 0.0f; }

bool coat_is_mirror(const Bsdf* b) { return b->coat_alpha < MIRROR_ALPHA; }

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

bool has_sheen(const Bsdf* b) { return HAS_SHEEN && max3(b->sheen) > 0.0f; }

/* E_s(mu): the sheen lobe's directional albedo for colour 1 (bilinear in kernels/sheen_albedo.h). */
float sheen_albedo_at(const Bsdf* b, float mu) {
    float x = clamp(mu * (float)SHEEN_ALBEDO_MU - 0.5f, 0.0f, (float)(SHEEN_ALBEDO_MU - 1));
    float y = clamp((b->sheen_r - SHEEN_MIN_ROUGHNESS) / (1.0f - SHEEN_MIN_ROUGHNESS) * (float)(SHEEN_ALBEDO_R - 1),
                    0.0f, (float)(SHEEN_ALBEDO_R - 1));
    int i = min((int)x, SHEEN_ALBEDO_MU - 2), j = min((int)y, SHEEN_ALBEDO_R - 2);
    float fx = x - (float)i, fy = y - (float)j;
    __constant float* r0 = sheen_albedo + j * SHEEN_ALBEDO_MU;
    __constant float* r1 = r0 + SHEEN_ALBEDO_MU;
    float a = r0[i] + (r0[i + 1] - r0[i]) * fx, c = r1[i] + (r1[i + 1] - r1[i]) * fx;
    return a + (c - a) * fy;
}

/* What the sheen leaves of the lobes under it. */
float sheen_scale(const Bsdf* b, float3 wo, float3 wi) {
    if (!has_sheen(b)) return 1.0f;
    float e = fmin(1.0f, fmax(sheen_albedo_at(b, fabs(dot(b->ns, wo))), sheen_albedo_at(b, fabs(dot(b->ns, wi)))));
    return fmax(0.0f, 1.0f - max3(b->sheen) * e);
}

/* The sheen lobe at (wo, wi), both above ns. */
float3 sheen_eval(const Bsdf* b, float3 wo, float3 wi) {
    float cos_o = dot(b->ns, wo), cos_i = dot(b->ns, wi);
    if (!(cos_o > 0.0f) || !(cos_i > 0.0f)) return (float3)(0.0f);
    float3 h = normalize(wo + wi);
    float ch = dot(b->ns, h), alpha = b->sheen_r * b->sheen_r;
    float d = (2.0f + 1.0f / alpha) * pow(fmax(0.0f, 1.0f - ch * ch), 0.5f / alpha) * (0.5f * INV_PI_F);
    float v = 1.0f / (4.0f * (cos_i + cos_o - cos_i * cos_o));
    float norm = fmax(1.0f, fmax(sheen_albedo_at(b, cos_o), sheen_albedo_at(b, cos_i)));
    return b->sheen * (d * v / norm);
}

/* What the coat and the sheen leave of the lobes under both. */
float layers_scale(const Bsdf* b, float3 wo, float3 wi) { return coat_scale(b, wo, wi) * sheen_scale(b, wo, wi); }

/* E(mu): the dielectric layer's directional albedo (exact Schlick for a mirror). */
float3 layer_albedo(const Bsdf* b, float mu, float alpha) {
    if (bsdf_is_mirror(b)) return b->f0 + (b->f90 - b->f0) * pow5(1.0f - mu);
    return b->f0 * ggx_table(ggx_albedo_a, mu, alpha) + (b->f90 - b->f0) * ggx_table(ggx_albedo_b, mu, alpha);
}

/* A table's hemispherical mean for the lobe, at the alpha dir_alpha gives (the cosine-weighted
 * mean of its directional values, so that the coupled terms integrate as they should). */
float ggx_avg(const Bsdf* b, __constant float* t) { return ggx_table_avg(t, b->alpha); }

/* E_avg = 2 int E(mu) mu dmu (Schlick's mean is F0 + (F90 - F0) / 21). */
float3 layer_albedo_avg(const Bsdf* b) {
    if (bsdf_is_mirror(b)) return b->f0 + (b->f90 - b->f0) * (1.0f / 21.0f);
    return b->f0 * ggx_avg(b, ggx_albedo_a_avg) + (b->f90 - b->f0) * ggx_avg(b, ggx_albedo_b_avg);
}

/* ---- lobes ------------------------------------------------------------------------------------ */

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

bool has_layer(const Bsdf* b) { return HAS_SPECULAR_LAYER && b->dielectric > 0.0f && b->f90 > 0.0f; }

/* KHR_materials_diffuse_transmission: part of the diffuse lobe reaches the other side. */
bool has_translucent(const Bsdf* b) { return HAS_DIFFUSE_TRANSMISSION && b->dt > 0.0f; }

/* The diffuse reflection's colour: the base, less the part turned to the other side. */
float3 diffuse_reflect_color(const Bsdf* b) { return has_translucent(b) ? b->base * (1.0f - b->dt) : b->base; }

/* Nothing but the Lambertian lobe (no layer, metal or glass): the fast paths below. */
bool bsdf_plain_lambert(const Bsdf* b) {
    if (has_coat(b) || has_sheen(b) || has_translucent(b)) return false;
    if (HAS_METAL && b->metal > 0.0f) return false;
    if (HAS_GLASS && b->glass > 0.0f) return false;
    return !has_layer(b);
}

bool has_irid(const Bsdf* b) { return HAS_IRIDESCENCE && b->irid > 0.0f; }

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

/* E(v) of the stretched metal lobe (F = 1), from above: the table holds an upper bound of the
 * albedo over (cos, azimuth from ta, alpha, stretch), multilinear in all four. */
float aniso_albedo(const Bsdf* b, float3 v) {
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
        e += wt *
             ggx_aniso_albedo[(((m + dm) * GGX_ANISO_ALPHA + k + dk) * GGX_ANISO_PHI + j + dj) * GGX_ANISO_MU + i + di];
    }
    return fmin(e, 1.0f);
}

/* The cosine-weighted mean of that bound over the hemisphere. */
float aniso_albedo_avg(const Bsdf* b) {
    float z = aniso_row(b), w = aniso_stretch(b);
    int k = min((int)z, GGX_ANISO_ALPHA - 2), m = min((int)w, GGX_ANISO_T - 2);
    float fz = z - (float)k, fw = w - (float)m;
    __constant float* r0 = ggx_aniso_albedo_avg + m * GGX_ANISO_ALPHA + k;
    __constant float* r1 = r0 + GGX_ANISO_ALPHA;
    float a = r0[0] + (r0[1] - r0[0]) * fz, c = r1[0] + (r1[1] - r1[0]) * fz;
    return a + (c - a) * fw;
}

float3 metal_ms_eval(const Bsdf* b, float3 wo, float3 wi, float cos_o, float cos_i, float al_o, float al_i) {
    /* A stretched lobe: Kulla-Conty on the upper bound of its albedo (kernels/ggx_aniso_albedo.h),
     * which gives back what the lobe loses, a little less, never more. */
    if (has_aniso(b)) {
        float a_avg = aniso_albedo_avg(b);
        if (!(1.0f - a_avg > 1e-6f)) return (float3)(0.0f);
        float s = (1.0f - aniso_albedo(b, wo)) * (1.0f - aniso_albedo(b, wi));
        return metal_ms_color(b, a_avg) * (b->metal * s * INV_PI_F / (1.0f - a_avg));
    }
    float a_avg = ggx_avg(b, ggx_albedo_a_avg);
    if (!(1.0f - a_avg > 1e-6f)) return (float3)(0.0f);
    float s = (1.0f - ggx_table(ggx_albedo_a, cos_o, al_o)) * (1.0f - ggx_table(ggx_albedo_a, cos_i, al_i));
    return metal_ms_color(b, a_avg) * (b->metal * s * INV_PI_F / (1.0f - a_avg));
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
        if (!mirror && has_aniso(b)) {
            float a_avg = aniso_albedo_avg(b);
            if (1.0f - a_avg > 1e-6f)
                w.metal_ms = b->metal * mean3(metal_ms_color(b, a_avg)) * (1.0f - aniso_albedo(b, wo));
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
                     metal_ms_eval(b, wo, wi, cos_o, cos_i, dir_alpha(b, wo), dir_alpha(b, wi));
        } else {
            if (layer) f += layer_fresnel(b, cos_d) * (b->dielectric * g);
            if (metal)
                f += metal_fresnel(b, cos_d) * (b->metal * g) +
                     metal_ms_eval(b, wo, wi, cos_o, cos_i, dir_alpha(b, wo), dir_alpha(b, wi));
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
    if (bsdf_plain_lambert(b)) { /* f cos / pdf is the albedo itself: no lobe to choose */
        if (!(mask & LOBE_DIFFUSE) || !(b->dielectric > 0.0f)) return false;
        s->wi = sample_cosine_hemisphere(b->ns, u1, u2);
        float cos_i = dot(b->ns, s->wi);
        if (cos_i <= 0.0f || dot(s->wi, b->ng) <= 0.0f) return false;
        s->pdf = cos_i * INV_PI_F;
        s->weight = b->base * b->dielectric;
        return true;
    }
    LobeWeights w = lobe_weights(b, wo, mask);
    float total = w.total;
    if (!(total > 0.0f)) return false;
    /* The technique, and u_lobe rescaled to [0, 1) within it (glass's reflect-or-refract choice):
     * the last technique with weight whose cumulative range holds u. */
    float u = u_lobe * total, acc = 0.0f, wt = 0.0f;
    int tech = -1;
    bool found = false;
#define CLPPM_PICK(field, id)                                                                                          \
    if (!found && w.field > 0.0f) {                                                                                    \
        tech = id;                                                                                                     \
        wt = w.field;                                                                                                  \
        if (u < acc + w.field) found = true;                                                                           \
        else acc += w.field;                                                                                           \
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
    if (!found) acc -= wt; /* u rounded past the end: the last technique */
    float u_in = clamp((u - acc) / wt, 0.0f, 0.99999994f);
    float p_tech = wt / total;
    bool mirror = bsdf_is_mirror(b);
    bool rough_glass = HAS_GLASS && tech == TECH_GLASS && glass_is_rough(b);
    if (HAS_GLASS && tech == TECH_GLASS && !rough_glass) {
        /* Reflect with probability F: the Fresnel weights cancel the probabilities. */
        float F = fresnel_dielectric(cos_o, b->eta);
        s->delta = true;
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
    if (mirror && (tech == TECH_LAYER || tech == TECH_METAL)) {
        s->delta = true;
        s->wi = bsdf_mirror(b, wo);
        float3 F = tech == TECH_LAYER ? layer_fresnel(b, cos_o) * b->dielectric : metal_fresnel(b, cos_o) * b->metal;
        s->weight = F * layers_scale(b, wo, s->wi) / p_tech;
        return true;
    }
    if (tech == TECH_COAT && coat_is_mirror(b)) { /* a smooth coat: its mirror, Fresnel at the view */
        s->delta = true;
        s->wi = reflect_dir(-wo, b->nc);
        if (dot(s->wi, b->ng) <= 0.0f || dot(s->wi, b->ns) <= 0.0f) return false;
        float cos_c = clamp(dot(b->nc, wo), 0.0f, 1.0f);
        s->weight = (float3)(b->coat * (COAT_F0 + (1.0f - COAT_F0) * pow5(1.0f - cos_c)) / p_tech);
        return true;
    }
    if (HAS_DIFFUSE_TRANSMISSION && tech == TECH_TRANSLUCENT) { /* the cosine about -ns */
        s->wi = sample_cosine_hemisphere(-b->ns, u1, u2);
        float cos_t = dot(b->ns, s->wi);
        if (cos_t >= 0.0f || dot(s->wi, b->ng) >= 0.0f) return false;
        s->below = true;
        s->pdf = bsdf_pdf_weighted(b, wo, s->wi, &w);
        if (!(s->pdf > 0.0f)) return false;
        s->weight = bsdf_eval(b, wo, s->wi, mask) * (-cos_t / s->pdf);
        return true;
    }
    if (rough_glass) {
        if (!glass_sample(b, wo, u_in, u1, u2, &s->wi, &s->below)) return false;
        if (s->below) { /* transmission: only the glass lobe reaches below */
            float cos_t = dot(b->ns, s->wi);
            if (dot(s->wi, b->ng) >= 0.0f) return false;
            s->pdf = bsdf_pdf_weighted(b, wo, s->wi, &w);
            if (!(s->pdf > 0.0f)) return false;
            s->weight = bsdf_eval(b, wo, s->wi, mask) * (-cos_t / s->pdf);
            return true;
        }
    } else if (tech == TECH_DIFFUSE || tech == TECH_METAL_MS || tech == TECH_SHEEN) {
        s->wi = sample_cosine_hemisphere(b->ns, u1, u2);
    } else if (tech == TECH_COAT) {
        float3 h = ggx_sample_h(b->nc, wo, b->coat_alpha, u1, u2);
        s->wi = normalize(2.0f * dot(wo, h) * h - wo);
    } else {
        float3 h = mf_sample_h(b, wo, u1, u2);
        s->wi = normalize(2.0f * dot(wo, h) * h - wo);
    }
    float cos_i = dot(b->ns, s->wi);
    if (cos_i <= 0.0f || dot(s->wi, b->ng) <= 0.0f) return false;
    if (!HAS_NON_DIFFUSE || (!has_coat(b) && !has_sheen(b) && !has_translucent(b) &&
                             ((mask & ~LOBE_DIFFUSE) == 0u || total == w.diffuse))) {
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

/* ---- a material at a surface ------------------------------------------------------------------ */

/* The glTF material at this surface (factors times textures), for a path that carries `transport`
 * (TRANSPORT_RADIANCE from the camera, TRANSPORT_IMPORTANCE from a light). */
Bsdf surface_bsdf(SCENE_PARAMS, const Surface* s, uint transport) {
    __global const Material* m = &materials[s->material];
    Bsdf b;
    b.radiance = transport == TRANSPORT_RADIANCE;
    b.ns = s->ns;
    b.ng = s->ng;
    b.nl = s->nl;
    b.base = surface_base_color(SCENE_ARGS, s);
    float metallic = HAS_METAL ? m->metallic : 0.0f;
    float r = m->roughness;
    if (HAS_TEXTURES && m->metallic_roughness_tex >= 0) { /* glTF: G is roughness, B metallic */
        float3 mr = texture_lookup(SCENE_ARGS, m->metallic_roughness_tex, s->uv);
        r *= mr.y;
        metallic *= mr.z;
    }
    float t = HAS_GLASS ? m->transmission : 0.0f;
    if (HAS_GLASS && HAS_TEXTURES && m->transmission_tex >= 0)
        t *= texture_lookup(SCENE_ARGS, m->transmission_tex, s->uv).x;
    b.metal = metallic;
    b.glass = (1.0f - metallic) * t;
    b.dielectric = (1.0f - metallic) * (1.0f - t);
    b.alpha = r * r;
    /* KHR_materials_ior and KHR_materials_specular: F0 = ((ior - 1) / (ior + 1))^2 times the
     * specular colour, at most 1, both F0 and F90 times the specular factor. */
    float q = (m->ior - 1.0f) / (m->ior + 1.0f);
    float spec = HAS_SPECULAR_LAYER ? m->specular_color[3] : 0.0f;
    float3 spec_color = load3g(m->specular_color);
    if (HAS_SPECULAR_LAYER && HAS_TEXTURES && m->specular_tex >= 0)
        spec *= texture_rgba(textures, texels, m->specular_tex, s->uv).w;
    if (HAS_SPECULAR_LAYER && HAS_TEXTURES && m->specular_color_tex >= 0)
        spec_color *= texture_lookup(SCENE_ARGS, m->specular_color_tex, s->uv);
    b.f0 = fmin(q * q * spec_color, (float3)(1.0f)) * spec;
    b.f90 = spec;
    b.thin = (m->flags & MATERIAL_FLAG_THIN_WALLED) != 0u;
    b.eta = s->front || b.thin ? m->ior : 1.0f / m->ior;
    b.front = s->front;
    b.sigma = HAS_VOLUME ? load3g(m->attenuation) : (float3)(0.0f);
    b.nc = s->nc;
    b.coat = HAS_CLEARCOAT ? m->clearcoat : 0.0f;
    b.coat_alpha = 0.0f;
    if (HAS_CLEARCOAT && b.coat > 0.0f) { /* clearcoatTexture's R, clearcoatRoughnessTexture's G */
        float cr = m->clearcoat_roughness;
        if (HAS_TEXTURES && m->clearcoat_tex >= 0) b.coat *= texture_lookup(SCENE_ARGS, m->clearcoat_tex, s->uv).x;
        if (HAS_TEXTURES && m->clearcoat_roughness_tex >= 0)
            cr *= texture_lookup(SCENE_ARGS, m->clearcoat_roughness_tex, s->uv).y;
        b.coat_alpha = cr * cr;
    }
    b.sheen = HAS_SHEEN ? load3g(m->sheen_color) : (float3)(0.0f);
    b.sheen_r = 1.0f;
    if (HAS_SHEEN && max3(b.sheen) > 0.0f) { /* sheenColorTexture's RGB, sheenRoughnessTexture's A */
        float sr = m->sheen_roughness;
        if (HAS_TEXTURES && m->sheen_color_tex >= 0) b.sheen *= texture_lookup(SCENE_ARGS, m->sheen_color_tex, s->uv);
        if (HAS_TEXTURES && m->sheen_roughness_tex >= 0)
            sr *= texture_rgba(textures, texels, m->sheen_roughness_tex, s->uv).w;
        b.sheen_r = fmax(sr, SHEEN_MIN_ROUGHNESS);
    }
    b.ta = s->ta;
    b.alpha_t = b.alpha;
    if (HAS_ANISOTROPY && m->anisotropy_strength > 0.0f) { /* anisotropyTexture's B scales the strength */
        float st = m->anisotropy_strength;
        if (HAS_TEXTURES && m->anisotropy_tex >= 0) st *= texture_rgba(textures, texels, m->anisotropy_tex, s->uv).z;
        if (st > 0.0f) {
            b.alpha = fmax(b.alpha, 1e-3f); /* a lobe of no width across would be singular */
            b.alpha_t = b.alpha + (1.0f - b.alpha) * st * st;
        }
    }
    b.irid = HAS_IRIDESCENCE ? m->iridescence : 0.0f;
    b.irid_ior = m->iridescence_ior;
    b.irid_d = m->iridescence_thickness[1];
    if (HAS_IRIDESCENCE && b.irid > 0.0f) { /* iridescenceTexture's R, iridescenceThicknessTexture's G */
        if (HAS_TEXTURES && m->iridescence_tex >= 0) b.irid *= texture_lookup(SCENE_ARGS, m->iridescence_tex, s->uv).x;
        if (HAS_TEXTURES && m->iridescence_thickness_tex >= 0) {
            float g = texture_lookup(SCENE_ARGS, m->iridescence_thickness_tex, s->uv).y;
            b.irid_d = m->iridescence_thickness[0] + (m->iridescence_thickness[1] - m->iridescence_thickness[0]) * g;
        }
    }
    b.dt = HAS_DIFFUSE_TRANSMISSION ? m->diffuse_transmission : 0.0f;
    b.translucent = (float3)(0.0f);
    if (HAS_DIFFUSE_TRANSMISSION && b.dt > 0.0f) { /* diffuseTransmissionTexture's A, the colour texture's RGB */
        if (HAS_TEXTURES && m->diffuse_transmission_tex >= 0)
            b.dt *= texture_rgba(textures, texels, m->diffuse_transmission_tex, s->uv).w;
        b.translucent = load3g(m->diffuse_transmission_color) * b.dt;
        if (HAS_TEXTURES && m->diffuse_transmission_color_tex >= 0)
            b.translucent *= texture_lookup(SCENE_ARGS, m->diffuse_transmission_color_tex, s->uv);
    }
    if (surface_is_unlit(SCENE_ARGS, s)) {
        b.dt = 0.0f;
        b.dielectric = b.glass = b.metal = b.coat = 0.0f;
        b.sheen = (float3)(0.0f);
    }
    return b;
}

/* KHR_materials_volume on a straight segment of length dist that leaves the surface along w (a
 * light sample's shadow ray, a connection): Beer-Lambert's exp(-sigma dist) when the segment runs
 * inside the surface's mesh, that is when w enters it through the front face or stays on the
 * inside of a back face; 1 elsewhere. Paths that are traced get the same factor on arrival
 * (volume_transmittance). */
float3 bsdf_segment_transmittance(const Bsdf* b, float3 w, float dist) {
    if (!HAS_VOLUME || !(max3(b->sigma) > 0.0f)) return (float3)(1.0f);
    bool inside = b->front ? dot(w, b->ng) < 0.0f : dot(w, b->ng) > 0.0f;
    return inside ? exp(-b->sigma * dist) : (float3)(1.0f);
}

#endif
