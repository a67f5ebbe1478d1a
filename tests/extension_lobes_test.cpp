// Each material extension's lobe on the device (kernels/bsdf.cl through tests/bsdf_kernels.h)
// against its specification's formula, written out here from the extension's text rather than
// from the kernels, at normal, middle and grazing angles, within 1% in value:
//  - KHR_materials_sheen: sheenColor D_Charlie V_Sheen (its "Sheen distribution" and "Sheen
//    visibility", alphaG the roughness squared as the Khronos sample viewer takes it; written out
//    in tests/bsdf_kernels.h, ref_sheen_d and ref_sheen_v), and the
//    layers under it scaled by min(1 - max3(sheenColor) E(VdotN), 1 - max3(sheenColor) E(LdotN)),
//    E the lobe's directional albedo by a quadrature of the formula here (not the kernels' table).
//  - KHR_materials_clearcoat: clearcoat fr(NdotV) times the specular BRDF V D of the coat's
//    roughness, fr Schlick's with F0 0.04 (the extension's fresnel_coat): at the mirror direction,
//    where the kernels' Fresnel at the half vector is the extension's at the normal; and the layers
//    under a smooth coat scaled by 1 - clearcoat fr(NdotV) where the view is the more grazing of
//    the two directions (the kernels take the larger albedo of the two, so that the model is
//    reciprocal; docs/scenes.md).
//  - KHR_materials_iridescence: the specular lobe's Fresnel mix(F_Schlick, F_iridescence,
//    iridescenceFactor) at the mirror direction, for a dielectric and for a metal, F_iridescence
//    the extension's evaluation (tests/iridescence_reference.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bsdf_kernels.h"
#include "iridescence_reference.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;
using namespace clppm::test::bsdf;

namespace {

// Directions about the test normal: wo in the (t, n) plane, wi at azimuth phi from wo's, both
// rounded to float as the device sees them.
struct Frame {
    D3 n = float_normal(), t, b;
    Frame() { host_frame(n, t, b); }
    D3 dir(double cos_theta, double phi) const {
        const double s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
        const D3 w = normalized(s * std::cos(phi) * t + s * std::sin(phi) * b + cos_theta * n);
        return {float(w.x), float(w.y), float(w.z)};
    }
};

// One direction's f.rgb from the device.
D3 device_f(const Params& p, const Frame& fr, D3 wo, D3 wi, unsigned mask) {
    std::vector<float> w;
    push3(w, wi);
    const std::vector<float> v = model_eval(p, fr.n, wo, w, mask);
    return {v[0], v[1], v[2]};
}

// ---- the extensions' formulas ----

// glTF 2.0 Appendix B's specular_brdf without its Fresnel: V_GGX D_GGX.
double spec_vd(double n_dot_l, double n_dot_v, double n_dot_h, double alpha) {
    const double a2 = alpha * alpha;
    const double v = 1 /
                     (n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1 - a2) + a2) +
                      n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1 - a2) + a2)) /
                     2;
    const double f = n_dot_h * n_dot_h * (a2 - 1) + 1;
    return v * a2 / (M_PI * f * f);
}
double spec_schlick(double f0, double f90, double c) { return f0 + (f90 - f0) * std::pow(1 - c, 5); }

double comp(D3 v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }
double rel(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(b), 1e-12); }

const double kCosines[] = {1.0, 0.6, 0.25, 0.08}; // normal to grazing (85 degrees)
const double kAzimuths[] = {0.0, M_PI / 2, M_PI};

} // namespace

TEST(ExtensionLobes, SheenIsTheCharlieLobeWithItsVisibility) {
    const Frame fr;
    const D3 color{0.9, 0.5, 0.2};
    double worst = 0;
    for (double r : {0.3, 0.6, 1.0}) {
        Params p;
        p.base = {0, 0, 0}, p.sheen = color, p.sheen_r = r;
        for (double co : kCosines)
            for (double ci : kCosines)
                for (double phi : kAzimuths) {
                    const D3 wo = fr.dir(co, 0), wi = fr.dir(ci, phi);
                    const D3 f = device_f(p, fr, wo, wi, kSheen);
                    const double nv = dot(fr.n, wo), nl = dot(fr.n, wi), nh = dot(fr.n, normalized(wo + wi));
                    const double s = ref_sheen_d(r, nh) * ref_sheen_v(nl, nv, r);
                    SCOPED_TRACE("roughness " + std::to_string(r) + " cos_o " + std::to_string(co) + " cos_i " +
                                 std::to_string(ci) + " phi " + std::to_string(phi));
                    for (int c = 0; c < 3; ++c) { // 1e-3 absolute: where h is the normal, float's h is not quite
                        const double want = comp(color, c) * s, got = comp(f, c);
                        EXPECT_NEAR(got, want, 0.01 * want + 1e-3) << "channel " << c;
                        if (want > 0.01) worst = std::max(worst, rel(got, want));
                    }
                }
    }
    std::printf("worst relative error where f > 0.01: %.2e\n", worst);
}

TEST(ExtensionLobes, SheenScalesTheLayersUnderItByItsAlbedo) {
    const Frame fr;
    const D3 color{0.5, 0.4, 0.2}; // max3 0.5
    for (double r : {0.3, 0.6, 1.0}) {
        Params bare;
        bare.base = {1, 1, 1}, bare.alpha = 0.5;
        Params p = bare;
        p.sheen = color, p.sheen_r = r;
        for (double co : kCosines) {
            const double eo = ref_sheen_albedo(co, r, 500);
            for (double ci : kCosines) {
                const double ei = ref_sheen_albedo(ci, r, 500);
                const D3 wo = fr.dir(co, 0), wi = fr.dir(ci, 2.0);
                const double want = std::min(1 - 0.5 * eo, 1 - 0.5 * ei);
                const double got = device_f(p, fr, wo, wi, kDiffuse).y / device_f(bare, fr, wo, wi, kDiffuse).y;
                EXPECT_LT(rel(got, want), 0.01) << "roughness " << r << " cos_o " << co << " cos_i " << ci << " E(o) "
                                                << eo << " E(i) " << ei << ": " << got << " against " << want;
            }
        }
    }
}

TEST(ExtensionLobes, ClearcoatIsFresnelAtTheNormalTimesItsSpecularBrdf) {
    const Frame fr;
    for (double roughness : {0.1, 0.3, 0.6})
        for (double co : kCosines) {
            Params p;
            p.base = {0, 0, 0}, p.coat = 0.8, p.coat_alpha = roughness * roughness;
            const D3 wo = fr.dir(co, 0), wi = fr.dir(co, M_PI); // the mirror direction
            const double nv = dot(fr.n, wo), nl = dot(fr.n, wi), nh = dot(fr.n, normalized(wo + wi));
            const double want = 0.8 * spec_schlick(0.04, 1, nv) * spec_vd(nl, nv, nh, roughness * roughness);
            const D3 f = device_f(p, fr, wo, wi, kCoat);
            EXPECT_LT(rel(f.y, want), 0.01)
                << "roughness " << roughness << " cos " << co << ": " << f.y << " against " << want;
            EXPECT_EQ(f.x, f.z);
        }
}

TEST(ExtensionLobes, SmoothClearcoatLeavesOneMinusItsFresnelOfTheLayersUnder) {
    const Frame fr;
    Params bare;
    bare.base = {0.8, 0.8, 0.8}, bare.alpha = 0.4;
    Params p = bare;
    p.coat = 0.7, p.coat_alpha = 0; // smooth: the coat's albedo is Schlick's Fresnel itself
    for (double co : kCosines)
        for (double ci : kCosines) {
            if (co > ci) continue; // the view the more grazing: min over both directions is the view's
            const D3 wo = fr.dir(co, 0), wi = fr.dir(ci, 1.0);
            const double want = 1 - 0.7 * spec_schlick(0.04, 1, dot(fr.n, wo));
            const double got = device_f(p, fr, wo, wi, kDiffuse).y / device_f(bare, fr, wo, wi, kDiffuse).y;
            EXPECT_LT(rel(got, want), 0.01) << "cos_o " << co << " cos_i " << ci << ": " << got << " against " << want;
        }
}

TEST(ExtensionLobes, IridescenceMixesTheFilmsFresnelIntoTheSpecularLobe) {
    const Frame fr;
    const double factor = 0.7, d = 400, ior = 1.3, alpha = 0.3 * 0.3;
    for (bool metal : {false, true})
        for (double co : kCosines) {
            Params p;
            p.alpha = alpha, p.irid = factor, p.irid_d = d, p.irid_ior = ior;
            if (metal) p.base = {0.9, 0.6, 0.3}, p.dielectric = 0, p.metal = 1;
            const D3 wo = fr.dir(co, 0), wi = fr.dir(co, M_PI);
            const double nv = dot(fr.n, wo), nl = dot(fr.n, wi), vh = dot(wo, normalized(wo + wi));
            const Rgb f0 = metal ? Rgb{0.9, 0.6, 0.3} : Rgb{0.04, 0.04, 0.04};
            const Rgb film = ref_irid_fresnel(ior, d, vh, f0);
            const D3 f = device_f(p, fr, wo, wi, metal ? kMetal : kSpecular);
            for (int c = 0; c < 3; ++c) {
                const double schlick = spec_schlick(f0[size_t(c)], 1, vh);
                const double want = ((1 - factor) * schlick + factor * film[size_t(c)]) * spec_vd(nl, nv, 1.0, alpha);
                const double got = comp(f, c);
                EXPECT_LT(rel(got, want), 0.01) << (metal ? "metal" : "dielectric") << " cos " << co << " channel " << c
                                                << ": " << got << " against " << want;
            }
        }
}
