// kernels/bsdf.cl, the whole glTF metallic-roughness model, on the device against a host reference
// in double written out from the formulas in bsdf.cl's header (glTF 2.0 Appendix B, Kulla and
// Conty 2017, Kelemen and Szirmay-Kalos 2001): eval against the reference, reciprocity, the
// sampler's histogram against bsdf_pdf (chi-square), the sample weight against eval cos / pdf,
// white furnaces without gain (with and without a clearcoat), continuity at the mirror limit, and the albedo tables against an
// independent quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "bsdf_kernels.h"
#include "ggx_albedo.h"
#include "ggx_aniso_albedo.h"
#include "iridescence_reference.h"
#include "sheen_albedo.h"
#include "stat_tests.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;
using namespace clppm::test::bsdf;

namespace {

Params dielectric(double alpha, D3 base = {0.8, 0.5, 0.2}) {
    Params p;
    p.alpha = alpha;
    p.base = base;
    return p;
}
Params metal(double alpha, D3 base = {0.95, 0.64, 0.54}) {
    Params p;
    p.alpha = alpha, p.base = base, p.dielectric = 0, p.metal = 1;
    return p;
}
Params mixed(double alpha) { // metallic 0.4, transmission 0.25, a tinted specular colour
    Params p;
    p.alpha = alpha, p.base = {0.7, 0.6, 0.3}, p.f0 = {0.04, 0.02, 0.01}, p.f90 = 0.8;
    p.metal = 0.4, p.dielectric = 0.6 * 0.75, p.glass = 0.6 * 0.25;
    return p;
}

// ---- the host reference ----------------------------------------------------------------------

// Bilinear in the generated table, in double (the table's data is checked separately below).
double table(const float* t, double mu, double alpha) {
    double x = std::clamp(mu * GGX_ALBEDO_MU - 0.5, 0.0, GGX_ALBEDO_MU - 1.0);
    double y = std::clamp(std::sqrt(alpha) * (GGX_ALBEDO_ALPHA - 1), 0.0, GGX_ALBEDO_ALPHA - 1.0);
    int i = std::min(int(x), GGX_ALBEDO_MU - 2), j = std::min(int(y), GGX_ALBEDO_ALPHA - 2);
    double fx = x - i, fy = y - j;
    auto at = [&](int a, int b) { return double(t[b * GGX_ALBEDO_MU + a]); };
    return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) +
           fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
}
double table_avg(const float* t, double alpha) {
    double y = std::clamp(std::sqrt(alpha) * (GGX_ALBEDO_ALPHA - 1), 0.0, GGX_ALBEDO_ALPHA - 1.0);
    int j = std::min(int(y), GGX_ALBEDO_ALPHA - 2);
    return (1 - (y - j)) * t[j] + (y - j) * t[j + 1];
}

double comp(D3 v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

// kernels/bsdf_metal.cl aniso_table, aniso_albedo and aniso_albedo_avg, in double: the stretched
// lobe's tables (its albedo bound, its multiple scattering's scale), multilinear in (cos, azimuth
// from t, roughness, stretch).
double aniso_row(double alpha) {
    return std::clamp(std::sqrt(alpha) * (GGX_ANISO_ALPHA - 1), 0.0, GGX_ANISO_ALPHA - 1.0);
}
double aniso_stretch(double alpha, double alpha_t) {
    const double t = alpha < 1 ? (alpha_t - alpha) / (1 - alpha) : 0.0;
    return std::clamp(t * (GGX_ANISO_T - 1), 0.0, GGX_ANISO_T - 1.0);
}
double ref_aniso_table(const float* table, double alpha, double alpha_t, double lx, double ly, double lz) {
    const double x = std::sqrt(std::clamp(lz, 0.0, 1.0)) * (GGX_ANISO_MU - 1);
    const double y =
        std::clamp(std::atan2(std::fabs(ly), std::fabs(lx)) * 2 / M_PI * (GGX_ANISO_PHI - 1), 0.0, GGX_ANISO_PHI - 1.0);
    const double z = aniso_row(alpha), w = aniso_stretch(alpha, alpha_t);
    const int i = std::min(int(x), GGX_ANISO_MU - 2), j = std::min(int(y), GGX_ANISO_PHI - 2);
    const int k = std::min(int(z), GGX_ANISO_ALPHA - 2), m = std::min(int(w), GGX_ANISO_T - 2);
    double e = 0;
    for (int c = 0; c < 16; ++c) {
        const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1, dm = (c >> 3) & 1;
        const double wt = (di ? x - i : 1 - (x - i)) * (dj ? y - j : 1 - (y - j)) * (dk ? z - k : 1 - (z - k)) *
                          (dm ? w - m : 1 - (w - m));
        e += wt *
             table[size_t((((m + dm) * GGX_ANISO_ALPHA + k + dk) * GGX_ANISO_PHI + j + dj) * GGX_ANISO_MU + i + di)];
    }
    return e;
}
double ref_aniso_albedo(double alpha, double alpha_t, double lx, double ly, double lz) {
    return std::min(ref_aniso_table(ggx_aniso_albedo, alpha, alpha_t, lx, ly, lz), 1.0);
}
double ref_aniso_albedo_avg(double alpha, double alpha_t) {
    const double z = aniso_row(alpha), w = aniso_stretch(alpha, alpha_t);
    const int k = std::min(int(z), GGX_ANISO_ALPHA - 2), m = std::min(int(w), GGX_ANISO_T - 2);
    auto at = [&](int kk, int mm) { return double(ggx_aniso_albedo_avg[size_t(mm * GGX_ANISO_ALPHA + kk)]); };
    const double a = at(k, m) + (at(k + 1, m) - at(k, m)) * (z - k);
    const double c = at(k, m + 1) + (at(k + 1, m + 1) - at(k, m + 1)) * (z - k);
    return a + (c - a) * (w - m);
}

// One channel c of f(wo, wi) over the lobes under the coat in mask (non-delta parts).
double ref_under(const Params& p, D3 n, D3 wo, D3 wi, unsigned mask, int c) {
    double co = dot(n, wo), ci = dot(n, wi);
    // KHR_materials_anisotropy: alpha_t along the kernel's make_frame tangent, the tables at
    // sqrt(alpha_t alpha).
    const bool aniso = p.alpha_t >= 0 && p.alpha_t != p.alpha;
    const double at = aniso ? p.alpha_t : p.alpha;
    const D3 tt = kernel_tangent(n), tb = cross(n, tt);
    auto al = [&](D3) { return p.alpha; }; // the tables at the smaller alpha, across the stretch
    auto avg = [&](const float* t) { return table_avg(t, p.alpha); };
    const double al_o = al(wo), al_i = al(wi);
    const bool mirror = std::max(p.alpha, at) < 1e-4;
    const double base = comp(p.base, c), f0 = comp(p.f0, c), f90 = p.f90;
    double glass = 0;
    if ((mask & kGlass) && p.glass > 0 && !mirror && (p.thin || std::fabs(p.eta - 1) > 1e-3))
        glass = p.glass * ref_rough_glass(n, wo, wi, p.alpha, p.eta, p.thin, base);
    const bool translucent = p.dt > 0 && (mask & kDiffuse) && co > 0 && ci < 0;
    if (!translucent && (co <= 0 || ci <= 0)) return glass;
    auto E = [&](double mu, double a) {
        return mirror ? f0 + (f90 - f0) * std::pow(1 - mu, 5)
                      : f0 * table(ggx_albedo_a, mu, a) + (f90 - f0) * table(ggx_albedo_b, mu, a);
    };
    const double e_avg =
        mirror ? f0 + (f90 - f0) / 21 : f0 * avg(ggx_albedo_a_avg) + (f90 - f0) * avg(ggx_albedo_b_avg);
    // KHR_materials_iridescence: the film's Fresnel over the layer's F0 (times F90) or the metal's.
    auto film = [&](double cos_d, bool metal) {
        if (metal) return ref_irid_fresnel(p.irid_ior, p.irid_d, cos_d, {p.base.x, p.base.y, p.base.z});
        Rgb r = ref_irid_fresnel(p.irid_ior, p.irid_d, cos_d, {p.f0.x / f90, p.f0.y / f90, p.f0.z / f90});
        for (double& v : r) v *= f90;
        return r;
    };
    double f = glass;
    // KHR_materials_diffuse_transmission: (1 - dt) base above, dt dt_colour below, both coupled to
    // the layer at |cos_i|.
    const double dcolor = translucent ? p.dt * comp(p.dt_color, c) : (1 - p.dt) * base;
    if (translucent) ci = -ci;
    if (mask & kDiffuse) {
        const double c0 = p.dielectric * dcolor / M_PI;
        double d = c0;
        if (p.dielectric > 0 && f90 > 0) {
            d *= 1 - e_avg > 1e-6 ? (1 - E(co, al_o)) * (1 - E(ci, al_i)) / (1 - e_avg) : 0;
            if (p.irid > 0) {                           // under the film: min(1 - E_f(o), 1 - E_f(i)), per channel
                auto ef = [&](double mu, double al_v) { // A(mu) F_film(x), (1 - x)^5 = B(mu) / A(mu)
                    if (mirror) return film(mu, false)[size_t(c)];
                    const double a = table(ggx_albedo_a, mu, al_v), b = table(ggx_albedo_b, mu, al_v);
                    const double x = a > 1e-6 ? 1 - std::pow(std::clamp(b / a, 0.0, 1.0), 0.2) : mu;
                    return std::min(1.0, a * 1.03 * film(x, false)[size_t(c)]);
                };
                d = (1 - p.irid) * d + p.irid * c0 * std::max(0.0, 1 - std::max(ef(co, al_o), ef(ci, al_i)));
            }
        }
        f += d;
    }
    if (mirror || translucent) return f;
    D3 h = normalized(wo + wi);
    double dg = ref_d(dot(n, h), p.alpha) / (1 + ref_lambda(co, p.alpha) + ref_lambda(ci, p.alpha)) / (4 * co * ci);
    if (aniso) { // Heitz 2014, Eqs. 80 and 86, in the frame (t, cross(n, t), n)
        const D3 t = tt, b = tb;
        auto lambda = [&](D3 v) {
            const double x = dot(v, t), y = dot(v, b), z = dot(v, n);
            return 0.5 * (-1 + std::sqrt(1 + (at * at * x * x + p.alpha * p.alpha * y * y) / (z * z)));
        };
        const double x = dot(h, t) / at, y = dot(h, b) / p.alpha, z = dot(h, n), q = x * x + y * y + z * z;
        dg = 1 / (M_PI * at * p.alpha * q * q) / (1 + lambda(wo) + lambda(wi)) / (4 * co * ci);
    }
    const double s5 = std::pow(1 - dot(wi, h), 5);
    const double cos_d = dot(wi, h);
    if ((mask & kSpecular) && f90 > 0) {
        double F = f0 + (f90 - f0) * s5;
        if (p.irid > 0) F = (1 - p.irid) * F + p.irid * film(cos_d, false)[size_t(c)];
        f += p.dielectric * F * dg;
    }
    if ((mask & kMetal) && p.metal > 0) {
        double F = base + (1 - base) * s5;
        if (p.irid > 0) F = (1 - p.irid) * F + p.irid * film(cos_d, true)[size_t(c)];
        f += p.metal * F * dg;
        const double a_avg = avg(ggx_albedo_a_avg);
        const double f_avg = base + (1 - base) / 21;
        double f_ms = f_avg * f_avg * a_avg / (1 - f_avg * (1 - a_avg));
        if (p.irid > 0) { // the film's part: F_avg its Fresnel at cos 0.456
            const double g = std::min(1.0, film(0.456, true)[size_t(c)]);
            f_ms = (1 - p.irid) * f_ms + p.irid * g * g * a_avg / (1 - g * (1 - a_avg));
        }
        if (aniso) { // Kulla-Conty on the stretched lobe's albedo bound
            const double b_avg = ref_aniso_albedo_avg(p.alpha, at);
            double g_ms = 0;
            const double fa = base + (1 - base) / 21;
            g_ms = fa * fa * b_avg / (1 - fa * (1 - b_avg));
            if (p.irid > 0) {
                const double g = std::min(1.0, film(0.456, true)[size_t(c)]);
                g_ms = (1 - p.irid) * g_ms + p.irid * g * g * b_avg / (1 - g * (1 - b_avg));
            }
            auto e = [&](D3 v) { return ref_aniso_albedo(p.alpha, at, dot(v, tt), dot(v, tb), dot(v, n)); };
            auto k = [&](D3 v) {
                return ref_aniso_table(ggx_aniso_ms_scale, p.alpha, at, dot(v, tt), dot(v, tb), dot(v, n));
            };
            // Kulla-Conty's broad term, and the lobe reweighted, 1 - alpha / alpha_t of it
            const double share = 1 - p.alpha / std::max(at, p.alpha);
            if (1 - b_avg > 1e-6)
                f += p.metal * g_ms *
                     ((1 - share) * (1 - e(wo)) * (1 - e(wi)) / (M_PI * (1 - b_avg)) + share * k(wo) * k(wi) * dg);
        } else if (1 - a_avg > 1e-6) {
            f += p.metal * f_ms * (1 - table(ggx_albedo_a, co, al_o)) * (1 - table(ggx_albedo_a, ci, al_i)) /
                 (M_PI * (1 - a_avg));
        }
    }
    return f;
}

// The coat's directional albedo: Schlick with F0 0.04 and F90 1.
double coat_albedo(const Params& p, double mu) {
    mu = std::clamp(mu, 0.0, 1.0);
    if (p.coat_alpha < 1e-4) return 0.04 + 0.96 * std::pow(1 - mu, 5);
    return 0.04 * table(ggx_albedo_a, mu, p.coat_alpha) + 0.96 * table(ggx_albedo_b, mu, p.coat_alpha);
}

// The sheen lobe's albedo, bilinear in the generated table.
double sheen_albedo_ref(const Params& p, double mu) {
    double x = std::clamp(mu * SHEEN_ALBEDO_MU - 0.5, 0.0, SHEEN_ALBEDO_MU - 1.0);
    double y = std::clamp((p.sheen_r - SHEEN_MIN_ROUGHNESS) / (1 - SHEEN_MIN_ROUGHNESS) * (SHEEN_ALBEDO_R - 1), 0.0,
                          SHEEN_ALBEDO_R - 1.0);
    int i = std::min(int(x), SHEEN_ALBEDO_MU - 2), j = std::min(int(y), SHEEN_ALBEDO_R - 2);
    double fx = x - i, fy = y - j;
    auto at = [&](int a, int b) { return double(sheen_albedo[b * SHEEN_ALBEDO_MU + a]); };
    return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) +
           fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
}

// The whole model: the rest times min(1 - max(sheen) E'(o), 1 - max(sheen) E'(i)) plus the sheen's
// Charlie lobe, all that times min(1 - coat E_c(o), 1 - coat E_c(i)), plus the coat's GGX lobe.
double ref_model(const Params& p, D3 n, D3 wo, D3 wi, unsigned mask, int c) {
    double f = ref_under(p, n, wo, wi, mask, c);
    const double co = dot(n, wo), ci = dot(n, wi);
    const double smax = std::max({p.sheen.x, p.sheen.y, p.sheen.z});
    if (smax > 0) {
        const double eo = sheen_albedo_ref(p, std::fabs(co)), ei = sheen_albedo_ref(p, std::fabs(ci));
        f *= std::max(0.0, 1 - smax * std::min(1.0, std::max(eo, ei)));
        if ((mask & kSheen) && co > 0 && ci > 0) {
            D3 h = normalized(wo + wi);
            const double dv = ref_sheen_d(p.sheen_r, dot(n, h)) * ref_sheen_v(ci, co, p.sheen_r);
            f += comp(p.sheen, c) * dv / std::max({1.0, eo, ei});
        }
    }
    if (p.coat <= 0) return f;
    f *= std::max(0.0, 1 - p.coat * std::max(coat_albedo(p, std::fabs(co)), coat_albedo(p, std::fabs(ci))));
    if ((mask & kCoat) && p.coat_alpha >= 1e-4 && co > 0 && ci > 0) {
        D3 h = normalized(wo + wi);
        const double a = p.coat_alpha;
        f += p.coat * (0.04 + 0.96 * std::pow(1 - dot(wi, h), 5)) * ref_d(dot(n, h), a) /
             (1 + ref_lambda(co, a) + ref_lambda(ci, a)) / (4 * co * ci);
    }
    return f;
}

Params coated(Params p, double coat, double coat_alpha) {
    p.coat = coat, p.coat_alpha = coat_alpha;
    return p;
}

Params stretched(Params p, double alpha_t) {
    p.alpha = std::max(p.alpha, 1e-3); // as surface_bsdf keeps an anisotropic lobe's width
    p.alpha_t = alpha_t;
    return p;
}

Params filmed(Params p, double irid, double d, double ior = 1.3) {
    p.irid = irid, p.irid_d = d, p.irid_ior = ior;
    return p;
}

Params sheened(Params p, D3 sheen, double r) {
    p.sheen = sheen, p.sheen_r = r;
    return p;
}

Params translucent(Params p, double dt, D3 color) {
    p.dt = dt, p.dt_color = color;
    return p;
}

Params glass(double alpha, double eta, bool thin = false) {
    Params p;
    p.alpha = alpha, p.base = {0.9, 0.8, 0.6}, p.dielectric = 0, p.glass = 1, p.eta = eta, p.thin = thin;
    return p;
}

const std::vector<Params>& cases() {
    static const std::vector<Params> c = {
        dielectric(0.05),
        dielectric(0.25),
        dielectric(1.0),
        metal(0.05),
        metal(0.3),
        metal(1.0),
        mixed(0.1),
        mixed(0.6),
        glass(0.1, 1.5),
        glass(0.5, 1 / 1.5),
        glass(0.3, 1.5, true),
        coated(dielectric(0.5), 1.0, 0.05),
        coated(metal(0.3), 0.7, 0.3),
        coated(glass(0.3, 1.5), 0.5, 0.2),
        coated(dielectric(0.2), 0.8, 1.0),
        sheened(dielectric(0.6), {0.9, 0.5, 0.2}, 0.5),
        sheened(metal(0.4), {1, 1, 1}, 0.2),
        coated(sheened(dielectric(0.7), {0.6, 0.6, 0.9}, 1.0), 0.6, 0.1),
        filmed(dielectric(0.3), 1.0, 350),
        filmed(metal(0.2), 0.7, 500, 1.8),
        filmed(mixed(0.5), 0.5, 250),
        stretched(dielectric(0.05), 0.4),
        stretched(metal(0.1), 0.7),
        stretched(filmed(metal(0.2), 0.6, 300), 0.5),
        translucent(dielectric(0.3), 0.4, {0.9, 0.6, 0.3}),
        translucent(dielectric(0.01), 1.0, {0.5, 0.9, 0.7}),
        translucent(mixed(0.4), 0.7, {1, 1, 1}),
        coated(sheened(translucent(dielectric(0.5), 0.5, {0.3, 0.8, 0.4}), {0.5, 0.5, 0.5}, 0.6), 0.7, 0.2),
        translucent(filmed(dielectric(0.2), 0.8, 400), 0.6, {1, 0.5, 0.5})};
    return c;
}

} // namespace

// bsdf_eval against the double reference for every lobe set, at random directions (a quarter of
// them below the surface, where f is 0). Relative 3e-3 plus 1e-6 of the largest value, as for
// GGX alone (tests/ggx_test.cpp explains the float error near the peak).
TEST(BsdfModel, EvalMatchesHostReference) {
    const D3 n = float_normal();
    for (const Params& p : cases())
        for (double cos_o : kViews)
            for (unsigned mask : {kAll, kDiffuse, kSpecular | kMetal, kGlass, kCoat, kSheen}) {
                SCOPED_TRACE(p.name() + " cos_o " + std::to_string(cos_o) + " mask " + std::to_string(mask));
                D3 wo = view(cos_o);
                std::vector<float> wi = random_directions(n, 400, 7);
                std::vector<float> v = model_eval(p, n, wo, wi, mask);
                double peak = 0;
                for (size_t i = 0; i < 400; ++i) peak = std::max(peak, double(v[4 * i]));
                for (size_t i = 0; i < 400; ++i) {
                    D3 w = at3(wi, i);
                    if (std::fabs(dot(w, n)) < 1e-4) continue;
                    for (int c = 0; c < 3; ++c) {
                        double want = ref_model(p, n, wo, w, mask, c);
                        ASSERT_NEAR(v[4 * i + c], want, 3e-3 * want + 1e-6 * peak + 1e-9)
                            << "wi " << i << " channel " << c;
                    }
                }
            }
}

// f(wo, wi) = f(wi, wo): photons sample the BSDF from their side and the gather evaluates it from
// the eye's, so the model must be reciprocal (the coupled diffuse and Kulla-Conty terms are).
TEST(BsdfModel, EvalIsReciprocal) {
    const D3 n = float_normal();
    std::vector<float> dirs = random_directions(n, 64, 11);
    for (const Params& p : cases())
        for (size_t a = 0; a < 64; ++a) {
            D3 wo = at3(dirs, a);
            if (dot(wo, n) <= 1e-3) continue;
            std::vector<float> fwd = model_eval(p, n, wo, dirs, kAll);
            for (size_t b = 0; b < 64; ++b) {
                D3 wi = at3(dirs, b);
                // Diffuse transmission: light from below, seen from below (the normal turned over;
                // rough glass's refraction is reciprocal only with the index inverted as well).
                const bool through = p.dt > 0 && p.glass == 0 && dot(wi, n) < -1e-3;
                if (dot(wi, n) <= 1e-3 && !through) continue;
                std::vector<float> one;
                push3(one, wo);
                std::vector<float> back = model_eval(p, through ? -1.0 * n : n, wi, one, kAll);
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(fwd[4 * b + c], back[c], 2e-3 * std::fabs(back[c]) + 1e-7)
                        << p.name() << " pair " << a << "," << b << " channel " << c;
            }
        }
}

// Histogram of bsdf_sample's directions against bsdf_pdf integrated over the bins (Pearson's
// chi-square, Sidak-corrected over all cases). Bins are cells of the half-vector grid about the
// lobes' alpha, so the peak is resolved; samples that are not drawn (below the surface, or from
// a delta lobe, or transmitted through glass) go to one extra cell whose expectation is the rest of
// the mass.
TEST(BsdfModel, SampleMatchesPdfChiSquare) {
    const D3 n = float_normal();
    const int nu = 16, nphi = 32;
    const double level = sidak(1e-3, int(cases().size() * 3 * 2));
    for (const Params& p : cases())
        for (double cos_o : kViews)
            for (unsigned mask : {kAll, kDiffuse | kMetal}) {
                SCOPED_TRACE(p.name() + " cos_o " + std::to_string(cos_o) + " mask " + std::to_string(mask));
                D3 wo = view(cos_o);
                // Not narrower than 0.15: the diffuse part would crowd into the last bins in u.
                HalfVectorGrid grid(n, wo, std::max(p.alpha, 0.15));
                Quadrature q = half_vector_quadrature(grid, 4 * nu, 4 * nphi);
                std::vector<float> v = model_eval(p, n, wo, q.wi, mask);
                const size_t m = 200000;
                std::vector<double> expected = expected_bin_counts(q, v, 4, 3, nu, nphi, 4, m);
                std::vector<double> observed(nu * nphi + 1, 0);
                std::vector<float> s = model_sample(p, n, wo, m, mask, 100 + uint64_t(cos_o * 10) + mask);
                for (size_t i = 0; i < m; ++i) {
                    int flags = int(s[8 * i + 7]);
                    if (!(flags & 1) || (flags & 2) || (flags & 4)) { // transmission: tests/rough_glass_test.cpp
                        observed[nu * nphi] += 1;
                        continue;
                    }
                    observed[grid.cell(D3{s[8 * i], s[8 * i + 1], s[8 * i + 2]}, nu, nphi)] += 1;
                }
                Chi2Result c = chi2_test(observed, expected);
                EXPECT_TRUE(c.error.empty()) << c.error;
                EXPECT_GT(c.p_value, level) << "chi2 " << c.chi2 << " dof " << c.dof;
            }
}

// A drawn sample's weight is eval cos / pdf at its direction, and its pdf is bsdf_pdf there (so
// the path tracer's MIS weights and estimators that use eval and pdf agree with sampling).
TEST(BsdfModel, SampleWeightIsEvalCosOverPdf) {
    const D3 n = float_normal();
    for (const Params& p : cases())
        for (double cos_o : kViews) {
            SCOPED_TRACE(p.name() + " cos_o " + std::to_string(cos_o));
            D3 wo = view(cos_o);
            const size_t m = 2000;
            std::vector<float> s = model_sample(p, n, wo, m, kAll, 5);
            std::vector<float> wi;
            for (size_t i = 0; i < m; ++i) push3(wi, D3{s[8 * i], s[8 * i + 1], s[8 * i + 2]});
            std::vector<float> v = model_eval(p, n, wo, wi, kAll);
            for (size_t i = 0; i < m; ++i) {
                int flags = int(s[8 * i + 7]);
                if (!(flags & 1) || (flags & 2)) continue;
                const double cos_i = std::fabs(dot(at3(wi, i), n)), pdf = v[4 * i + 3];
                ASSERT_NEAR(s[8 * i + 6], pdf, 1e-3 * pdf) << "sample " << i;
                for (int c = 0; c < 3; ++c) {
                    const double want = v[4 * i + c] * cos_i / pdf;
                    // A film's Fresnel swings fast with the angle near its zeros: a direction
                    // rounded to float moves it by up to 3e-7 there.
                    ASSERT_NEAR(s[8 * i + 3 + c], want, 1e-3 * want + (p.irid > 0 ? 1e-6 : 1e-7))
                        << "sample " << i << " channel " << c;
                }
            }
        }
}

namespace {

// The mean weight (f cos / pdf, the G of model_sample's output) of m samples, counting those not
// drawn as 0: the albedo the sampler sees, with its standard error in *se.
double sampled_albedo(const std::vector<float>& s, size_t m, double* se) {
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < m; ++i) {
        double w = int(s[8 * i + 7]) & 1 ? s[8 * i + 4] : 0.0;
        sum += w, sum2 += w * w;
    }
    const double mean = sum / m;
    *se = std::sqrt(std::max(0.0, sum2 / m - mean * mean) / m);
    return mean;
}

} // namespace

// White furnace: the albedo (the mean sample weight, delta lobes included) never exceeds 1, and a
// white metal or a white dielectric reflects everything at every roughness and view: the
// coupled diffuse takes exactly what the layer does not reflect, Kulla-Conty gives back what
// single-scattering GGX loses. Bounds: 4 standard errors plus 2e-3 for the albedo tables'
// interpolation.
TEST(BsdfModel, WhiteFurnaceWithoutGain) {
    const D3 n = float_normal();
    const size_t m = 400000;
    for (double alpha : {0.0, 0.01, 0.05, 0.2, 0.5, 1.0})
        for (double cos_o : {1.0, 0.7, 0.3, 0.05}) {
            std::vector<Params> white = {dielectric(alpha, {1, 1, 1}), metal(alpha, {1, 1, 1}),
                                         translucent(dielectric(alpha, {1, 1, 1}), 0.5, {1, 1, 1}),
                                         translucent(dielectric(alpha, {0, 0, 0}), 1.0, {1, 1, 1})};
            Params colored = mixed(alpha);
            colored.base = {1, 1, 1};
            for (const Params& p : white) {
                SCOPED_TRACE(p.name() + " cos_o " + std::to_string(cos_o));
                std::vector<float> s = model_sample(p, n, view(cos_o), m, kAll, 9 + uint64_t(alpha * 100));
                double se;
                const double mean = sampled_albedo(s, m, &se);
                EXPECT_LE(mean, 1 + 4 * se + 2e-3);
                // At grazing views the part of GGX's samples that falls below the horizon is lost
                // to the sampler as to the model; the tables cover it within 1%.
                EXPECT_GE(mean, (cos_o < 0.1 ? 0.99 : 0.997) - 4 * se);
            }
            // Under a coat (its alpha from 0 to 1 with the base's): never above 1; what the layering
            // loses (docs/scenes.md, "Materials") is at most the bound below.
            for (const Params& p :
                 {coated(dielectric(alpha, {1, 1, 1}), 1.0, alpha), coated(metal(alpha, {1, 1, 1}), 1.0, alpha),
                  coated(dielectric(alpha, {1, 1, 1}), 0.5, 1.0 - alpha),
                  sheened(dielectric(alpha, {1, 1, 1}), {1, 1, 1}, std::max(0.07, alpha)),
                  sheened(metal(alpha, {1, 1, 1}), {1, 1, 1}, 1.0 - 0.9 * alpha),
                  filmed(dielectric(alpha, {1, 1, 1}), 1.0, 300 + 400 * alpha, 2.0),
                  filmed(metal(alpha, {1, 1, 1}), 1.0, 200 + 400 * alpha),
                  stretched(dielectric(alpha, {1, 1, 1}), alpha + (1 - alpha) * 0.5),
                  stretched(metal(alpha, {1, 1, 1}), alpha + (1 - alpha) * 0.8)}) {
                SCOPED_TRACE(p.name() + " cos_o " + std::to_string(cos_o));
                std::vector<float> s = model_sample(p, n, view(cos_o), m, kAll, 17 + uint64_t(alpha * 100));
                double se;
                const double mean = sampled_albedo(s, m, &se);
                EXPECT_LE(mean, 1 + 4 * se + 2e-3);
                // The least measured: 0.969, a white Lambertian under a smooth coat seen head-on;
                // under a white sheen 0.865 (roughness 1, head-on): the extension's scaling takes
                // the sheen's albedo at the worse of the two directions.
                // Under a film 0.91 (white Lambertian, rough layer, head-on): its albedo is
                // estimated 3% over (kernels/bsdf_dielectric.cl film_layer_albedo).
                // A stretched metal's multiple scattering works on an upper bound of its albedo
                // (kernels/ggx_aniso_albedo.h): 0.989 at the least. The diffuse under a stretched
                // layer is coupled at the smaller alpha, which never gains but loses: at grazing
                // views it is scaled for the narrow lobe's Fresnel peak (0.32 at cos 0.05).
                const bool sheen = p.sheen.x > 0, film = p.irid > 0, stretched = p.alpha_t >= 0;
                const bool stretched_metal = stretched && p.metal > 0;
                EXPECT_GE(mean, (stretched_metal ? 0.98 : stretched ? 0.3 : sheen ? 0.85 : film ? 0.9 : 0.96) - 4 * se);
            }
            std::vector<float> s = model_sample(colored, n, view(cos_o), m, kAll, 13);
            for (int c = 0; c < 3; ++c) {
                double sum = 0, sum2 = 0;
                for (size_t i = 0; i < m; ++i) {
                    double w = int(s[8 * i + 7]) & 1 ? s[8 * i + 3 + c] : 0.0;
                    sum += w, sum2 += w * w;
                }
                const double mean = sum / m, se = std::sqrt(std::max(0.0, sum2 / m - mean * mean) / m);
                EXPECT_LE(mean, 1 + 4 * se + 2e-3) << colored.name() << " channel " << c;
            }
        }
}

// Diffuse transmission's half below the surface: the histogram of the samples drawn through it,
// mirrored up through the tangent plane, against bsdf_pdf at the mirrored cells' directions
// (chi-square as above; what is drawn above goes to the extra cell).
TEST(BsdfModel, TranslucentSamplesMatchPdfBelow) {
    const D3 n = float_normal();
    const int nu = 16, nphi = 32;
    const std::vector<Params> ps = {translucent(dielectric(0.3), 0.4, {0.9, 0.6, 0.3}),
                                    translucent(mixed(0.4), 0.7, {1, 1, 1}),
                                    coated(translucent(dielectric(0.5), 0.5, {0.3, 0.8, 0.4}), 0.7, 0.2)};
    const double level = sidak(1e-3, int(ps.size() * 3));
    for (const Params& p : ps)
        for (double cos_o : kViews) {
            SCOPED_TRACE(p.name() + " cos_o " + std::to_string(cos_o));
            D3 wo = view(cos_o);
            // The cells about the mirror image of wo, whose u grid is cosine-like far from it.
            HalfVectorGrid grid(n, wo, 0.5);
            Quadrature q = half_vector_quadrature(grid, 4 * nu, 4 * nphi);
            std::vector<float> below;
            for (size_t i = 0; i < q.weight.size(); ++i) {
                D3 w = at3(q.wi, i);
                push3(below, w - (2 * dot(w, n)) * n);
            }
            std::vector<float> v = model_eval(p, n, wo, below, kAll);
            const size_t m = 200000;
            std::vector<double> expected = expected_bin_counts(q, v, 4, 3, nu, nphi, 4, m);
            std::vector<double> observed(nu * nphi + 1, 0);
            ASSERT_GT(m - expected.back(), 0.05 * m); // the lobe below is sampled at all
            std::vector<float> s = model_sample(p, n, wo, m, kAll, 300 + uint64_t(cos_o * 10));
            for (size_t i = 0; i < m; ++i) {
                int flags = int(s[8 * i + 7]);
                if (!(flags & 1) || (flags & 2) || !(flags & 4)) {
                    observed[nu * nphi] += 1;
                    continue;
                }
                D3 w{s[8 * i], s[8 * i + 1], s[8 * i + 2]};
                observed[grid.cell(w - (2 * dot(w, n)) * n, nu, nphi)] += 1; // mirrored back above
            }
            Chi2Result c = chi2_test(observed, expected);
            EXPECT_TRUE(c.error.empty()) << c.error;
            EXPECT_GT(c.p_value, level) << "chi2 " << c.chi2 << " dof " << c.dof;
        }
}

// Continuous in roughness: just above MIRROR_ALPHA the GGX lobes reflect what the mirror does.
TEST(BsdfModel, GgxMeetsTheMirrorAtTheDeltaThreshold) {
    const D3 n = float_normal();
    for (double cos_o : {1.0, 0.5, 0.1}) {
        for (const Params& base : {dielectric(0), metal(0)}) {
            double albedo[2];
            for (int k = 0; k < 2; ++k) {
                Params p = base;
                p.alpha = k == 0 ? 0.0 : 1.2e-4;
                const size_t m = 100000;
                std::vector<float> s = model_sample(p, n, view(cos_o), m, kAll, 21);
                double sum = 0;
                for (size_t i = 0; i < m; ++i) sum += int(s[8 * i + 7]) & 1 ? s[8 * i + 3] : 0.0;
                albedo[k] = sum / m;
            }
            EXPECT_NEAR(albedo[1], albedo[0], 5e-3) << base.name() << " cos_o " << cos_o;
        }
    }
}

// The generated tables against an independent quadrature over wi (not over half vectors, as the
// generator integrates): A = int D G2 / (4 mu) dwi and B the same with (1 - wo.h)^5, at table
// nodes (no interpolation).
TEST(BsdfModel, AlbedoTablesMatchAnIndependentQuadrature) {
    const D3 n{0, 0, 1};
    for (int j : {12, 20, 31}) // roughness 0.39 and up: the lobe is wide enough for a plain grid over wi
        for (int i : {3, 16, 29}) {
            const double r = double(j) / (GGX_ALBEDO_ALPHA - 1), alpha = r * r, mu = (i + 0.5) / GGX_ALBEDO_MU;
            const D3 wo{std::sqrt(1 - mu * mu), 0, mu};
            double a = 0, b = 0;
            const int nc = 200, np = 200;
            for (int x = 0; x < nc; ++x)
                for (int y = 0; y < np; ++y)
                    for (int g = 0; g < 4; ++g)
                        for (int k = 0; k < 4; ++k) {
                            double ci = (x + kGlX[g]) / nc, phi = 2 * M_PI * (y + kGlX[k]) / np;
                            double si = std::sqrt(1 - ci * ci);
                            D3 wi{si * std::cos(phi), si * std::sin(phi), ci};
                            double w = kGlW[g] * kGlW[k] / nc * (2 * M_PI / np);
                            D3 h = normalized(wo + wi);
                            double f = ref_d(dot(n, h), alpha) / (1 + ref_lambda(mu, alpha) + ref_lambda(ci, alpha)) /
                                       (4 * mu * ci) * ci * w;
                            a += f;
                            b += f * std::pow(1 - dot(wo, h), 5);
                        }
            EXPECT_NEAR(ggx_albedo_a[j * GGX_ALBEDO_MU + i], a, 1e-3) << "alpha " << alpha << " mu " << mu;
            EXPECT_NEAR(ggx_albedo_b[j * GGX_ALBEDO_MU + i], b, 1e-3) << "alpha " << alpha << " mu " << mu;
        }
}

// The stretched lobe's albedo bound (scripts/make_ggx_aniso_albedo.cpp integrates over visible
// normals) against Gauss-Legendre over wi with Heitz 2014's anisotropic D and Lambda, at points
// between the nodes, where the lobe is wide enough for a plain grid over wi: never below the
// albedo (so the multiple scattering never gains), and within 2% above it (3.5% at grazing views).
TEST(BsdfModel, AnisotropicAlbedoTableBoundsAnIndependentQuadrature) {
    for (double r : {0.45, 0.7, 0.93})
        for (double t : {0.15, 0.5, 0.9})
            for (double mu : {0.13, 0.55, 0.97})
                for (double phi : {0.2, 0.9, 1.4}) {
                    const double alpha = r * r, alpha_t = alpha + (1 - alpha) * t;
                    const double so = std::sqrt(1 - mu * mu);
                    const D3 wo{so * std::cos(phi), so * std::sin(phi), mu};
                    auto lambda = [&](D3 v) {
                        return 0.5 * (-1 + std::sqrt(1 + (alpha_t * alpha_t * v.x * v.x + alpha * alpha * v.y * v.y) /
                                                             (v.z * v.z)));
                    };
                    double e = 0;
                    const int nc = 160, np = 320;
                    for (int x = 0; x < nc; ++x)
                        for (int y = 0; y < np; ++y)
                            for (int g = 0; g < 4; ++g)
                                for (int k = 0; k < 4; ++k) {
                                    const double ci = (x + kGlX[g]) / nc, pi = 2 * M_PI * (y + kGlX[k]) / np;
                                    const double si = std::sqrt(1 - ci * ci);
                                    const D3 wi{si * std::cos(pi), si * std::sin(pi), ci};
                                    const D3 h = normalized(wo + wi);
                                    const double hx = h.x / alpha_t, hy = h.y / alpha,
                                                 q = hx * hx + hy * hy + h.z * h.z;
                                    const double d = 1 / (M_PI * alpha_t * alpha * q * q);
                                    e += d / (1 + lambda(wo) + lambda(wi)) / (4 * mu) * kGlW[g] * kGlW[k] / nc *
                                         (2 * M_PI / np);
                                }
                    const double bound = ref_aniso_albedo(alpha, alpha_t, wo.x, wo.y, wo.z);
                    SCOPED_TRACE("alpha " + std::to_string(alpha) + " alpha_t " + std::to_string(alpha_t) + " mu " +
                                 std::to_string(mu) + " phi " + std::to_string(phi));
                    EXPECT_GE(bound, e - 1e-3);
                    EXPECT_LE(bound, e + (mu < 0.2 ? 0.035 : 0.02)); // looser where E bends at grazing
                }
}

// The sheen table (scripts/make_sheen_albedo.cpp integrates over cos_i and phi by Gauss-Legendre)
// against a midpoint rule over (theta_i, phi), at table nodes where the lobe is wide enough for it.
TEST(BsdfModel, SheenAlbedoTableMatchesAnIndependentQuadrature) {
    for (int j : {10, 20, 31})
        for (int i : {3, 16, 29}) {
            const double r = SHEEN_MIN_ROUGHNESS + (1 - SHEEN_MIN_ROUGHNESS) * j / (SHEEN_ALBEDO_R - 1);
            const double mu = (i + 0.5) / SHEEN_ALBEDO_MU;
            const double e = ref_sheen_albedo(mu, r, 600);
            EXPECT_NEAR(sheen_albedo[j * SHEEN_ALBEDO_MU + i], e, 2e-3 * std::max(1.0, e))
                << "roughness " << r << " mu " << mu;
        }
}
