// Rough surfaces against the ground truth, Heitz et al. 2016's random walk on the Smith
// microsurface (tests/microsurface_walk.h): the walk first checked against the closed form of
// single scattering, then the kernels' white metal, stretched by KHR_materials_anisotropy, against
// the walk direction by direction (issue 62: a near-line lobe must send what it scatters twice
// along its line, not glow over the whole hemisphere); round metals, white and coloured; rough
// glass against the dielectric walk's first order, with what it leaves out measured.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "bsdf_kernels.h"
#include "ggx_aniso_albedo.h"
#include "microsurface_walk.h"

using namespace clppm;
using namespace clppm::test;
using namespace clppm::test::bsdf;

namespace {

D3 polar(double theta_deg, double phi_deg) {
    const double t = theta_deg * M_PI / 180, p = phi_deg * M_PI / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// f cos(wo) of single-scattering GGX with height-correlated masking (Heitz 2014, Eq. 99).
double single_scattering(const Microsurface& s, D3 wi, D3 wo) {
    const D3 h = normalized(wi + wo);
    return s.fresnel(dot(wi, h)) * s.d(h) / (1 + s.lambda(wi) + s.lambda(wo)) / (4 * wi.z);
}

// The energy leaving into each of nu x nphi cells of equal solid angle (uniform in cos theta and
// azimuth) of the local frame.
struct Lobe {
    static constexpr int nu = 16, nphi = 32;
    std::vector<double> cells = std::vector<double>(nu * nphi);
    void add(D3 w, double energy) {
        if (!(w.z > 0) || !(energy > 0)) return;
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * M_PI;
        const int a = std::min(nu - 1, int(w.z * nu)), b = std::min(nphi - 1, int(phi / (2 * M_PI) * nphi));
        cells[size_t(a * nphi + b)] += energy;
    }
    double total() const {
        double t = 0;
        for (double c : cells) t += c;
        return t;
    }
};

// The walk's lobe from wi (local frame) over m walks, and the part of it after two or more bounces.
void walk_lobe(const Microsurface& s, D3 wi, size_t m, Lobe* all, Lobe* multiple) {
    std::mt19937_64 rng(62);
    for (size_t i = 0; i < m; ++i) {
        D3 out;
        double energy;
        const int bounces = s.walk(wi, rng, &out, &energy);
        all->add(out, energy / double(m));
        if (bounces >= 2) multiple->add(out, energy / double(m));
    }
}

// The kernels' white metal (roughness alpha across, alpha_t along the tangent) sampled from wo given
// in the local frame (x along the tangent, z the normal): its lobe in the same frame.
Lobe model_lobe(double alpha, double alpha_t, D3 wo_local, size_t m, D3 base = {1, 1, 1}, int channel = 0) {
    const D3 n = float_normal(), t = kernel_tangent(n), b = cross(n, t);
    Params p;
    p.base = base, p.dielectric = 0, p.metal = 1, p.alpha = alpha, p.alpha_t = alpha_t;
    const D3 wo = t * wo_local.x + b * wo_local.y + n * wo_local.z;
    const std::vector<float> s = model_sample(p, n, {float(wo.x), float(wo.y), float(wo.z)}, m, kMetal, 77);
    Lobe lobe;
    for (size_t i = 0; i < m; ++i) {
        if (!(int(s[8 * i + 7]) & 1)) continue;
        const D3 wi = d3(&s[8 * i]);
        lobe.add({dot(wi, t), dot(wi, b), dot(wi, n)}, s[8 * i + 3 + size_t(channel)] / double(m));
    }
    return lobe;
}

double l1(const Lobe& a, const Lobe& b) {
    double d = 0;
    for (size_t i = 0; i < a.cells.size(); ++i) d += std::fabs(a.cells[i] - b.cells[i]);
    return d;
}

} // namespace

// The walk's first vertex, estimated by next-event estimation, is the closed-form lobe.
TEST(MicrosurfaceWalk, FirstVertexIsSingleScattering) {
    struct Case {
        double ax, ay, f0, ti, pi, to, po;
    };
    for (const Case& c : {Case{0.5, 0.5, 1, 30, 0, 30, 180}, Case{0.5, 0.5, 0.6, 60, 0, 40, 160},
                          Case{0.8, 0.1, 1, 45, 30, 50, 230}, Case{0.3, 0.05, 1, 70, 80, 20, 250}}) {
        const Microsurface s{c.ax, c.ay, c.f0};
        const D3 wi = polar(c.ti, c.pi), wo = polar(c.to, c.po);
        std::mt19937_64 rng(5);
        double single = 0, multiple = 0;
        const int m = 200000;
        for (int k = 0; k < m; ++k) s.eval(wi, wo, rng, &single, &multiple);
        const double want = single_scattering(s, wi, wo);
        EXPECT_NEAR(single / m / want, 1.0, 0.01) << c.ax << " " << c.ay << " " << c.ti << " " << c.to;
        EXPECT_GT(multiple, 0.0);
    }
}

// The white stretched metal's lobe, single and multiple scattering together, against the walk's,
// cell by cell: the L1 distance over the walk's total. Single scattering is the same in both (the
// test above), so what differs is where the multiple scattering goes; Kulla-Conty's broad term alone
// put most of it in the wrong cells (the old errors in the message).
TEST(StretchedMetal, MultipleScatteringLeavesWhereTheWalkSendsIt) {
    struct Case {
        double alpha, alpha_t, theta, phi, kulla_conty; // the L1 error of Kulla-Conty's term alone
    };
    const size_t m = 1000000;
    for (const Case& c : {Case{0.02, 1.0, 30, 60, 0.770}, Case{0.1, 1.0, 45, 30, 0.458}, Case{0.05, 0.5, 45, 30, 0.244},
                          Case{0.2, 0.6, 70, 45, 0.187}, Case{0.001, 1.0, 40, 70, 0.862}}) {
        const Microsurface s{c.alpha_t, c.alpha, 1};
        const D3 wo = polar(c.theta, c.phi);
        Lobe walk, walk_multiple;
        walk_lobe(s, wo, m, &walk, &walk_multiple);
        const Lobe model = model_lobe(c.alpha, c.alpha_t, wo, m);
        const double err = l1(model, walk) / walk.total();
        std::printf("alpha %.3f alpha_t %.2f view (%g, %g): walk %.4f (multiple %.4f), model %.4f, L1 %.3f\n", c.alpha,
                    c.alpha_t, c.theta, c.phi, walk.total(), walk_multiple.total(), model.total(), err);
        // Measured 0.03 to 0.10 (1,000,000 samples each; 0.19 to 0.86 with Kulla-Conty's term alone).
        EXPECT_LT(err, 0.15) << "Kulla-Conty alone: " << c.kulla_conty;
        EXPECT_NEAR(model.total(), walk.total(), 0.015); // the albedo bound's slack, as in the furnace
    }
}

// Roughness 0 at anisotropy strength 1: every facet normal lies in the plane of the tangent and the
// normal, so each bounce keeps the light's component across the tangent (it only flips): all the
// light leaves on the line wi_b = -wo_b, however often it bounced. Away from that line the lobe is
// black, as in the Khronos sample viewer's AnisotropyStrengthTest; Kulla-Conty's broad term lit it
// evenly (f cos 0.16 here).
TEST(StretchedMetal, ALineLobeIsBlackOffItsLine) {
    const D3 n = float_normal(), t = kernel_tangent(n), b = cross(n, t);
    Params p;
    p.base = {1, 1, 1}, p.dielectric = 0, p.metal = 1, p.alpha = 1e-3, p.alpha_t = 1;
    const D3 wo_local = polar(40, 70), wo = t * wo_local.x + b * wo_local.y + n * wo_local.z;
    std::vector<float> wi;
    std::vector<D3> local;
    for (double theta : {10.0, 35.0, 60.0, 80.0})
        for (double phi = 0; phi < 360; phi += 15) {
            const D3 w = polar(theta, phi);
            if (std::fabs(w.y + wo_local.y) < 0.1) continue; // on or near the line
            local.push_back(w);
            push3(wi, t * w.x + b * w.y + n * w.z);
        }
    const std::vector<float> f = model_eval(p, n, {float(wo.x), float(wo.y), float(wo.z)}, wi, kMetal);
    double worst = 0;
    for (size_t i = 0; i < local.size(); ++i) worst = std::max(worst, double(f[4 * i]) * local[i].z);
    EXPECT_LT(worst, 2e-3) << "f cos off the line";
    std::printf("largest f cos off the line: %.2e over %zu directions\n", worst, local.size());
}

// Round lobes, white and coloured: the isotropic metal's lobe (Kulla-Conty's term for its multiple
// scattering) against the walk's, cell by cell, from roughness 0.1 to 1 and views from the normal
// to grazing. A coloured metal is one walk per channel, Schlick's F0 that channel's base colour.
TEST(IsotropicMetal, MultipleScatteringLeavesWhereTheWalkSendsIt) {
    struct Case {
        double alpha, theta, base;
    };
    const size_t m = 1000000;
    for (const Case& c :
         {Case{0.1, 45, 1}, Case{0.25, 30, 1}, Case{0.5, 60, 1}, Case{1.0, 20, 1}, Case{1.0, 75, 1}, Case{0.5, 45, 0.3},
          Case{1.0, 45, 0.6}, Case{0.5, 45, 0.6}, Case{1.0, 45, 0.3}, Case{1.0, 45, 0.9}, Case{0.25, 60, 0.6}}) {
        const Microsurface s{c.alpha, c.alpha, c.base};
        const D3 wo = polar(c.theta, 0);
        Lobe walk, walk_multiple;
        walk_lobe(s, wo, m, &walk, &walk_multiple);
        const Lobe model = model_lobe(c.alpha, -1, wo, m, {0.9, c.base, 0.2}, 1);
        const double err = l1(model, walk) / walk.total();
        std::printf("alpha %.2f view %g base %.1f: walk %.4f (multiple %.4f), model %.4f, L1 %.3f\n", c.alpha, c.theta,
                    c.base, walk.total(), walk_multiple.total(), model.total(), err);
        // Measured 0.019 to 0.077 (1,000,000 samples and walks each).
        EXPECT_LT(err, 0.15);
        // White: within 0.001. Coloured: Kulla and Conty's F_ms (each extra bounce at Fresnel's
        // hemispherical average) keeps 80 to 85% of the walk's multiple scattering at roughness 1,
        // where the walk's later bounces meet the facets at grazing angles: 0.031 under at F0 0.6
        // and 0.9, 0.009 at 0.3; within 0.009 from roughness 0.5 down.
        EXPECT_NEAR(model.total(), walk.total(), c.base == 1 ? 0.002 : c.alpha >= 1 ? 0.035 : 0.012);
    }
}

// Rough glass against the dielectric walk, over the whole sphere of directions (transmission
// below). The kernels' glass lobe is single scattering (Walter et al. 2007): it must be the walk's
// first order, reflection and refraction alike, cell by cell; what it leaves out is the light
// that meets the microsurface more than once, which the test measures and prints (no energy
// compensation for rough glass yet: 0.2% of the light at alpha 0.1, 24% at alpha 1, a third
// from inside at alpha 0.6, where total internal reflection keeps light bouncing).
TEST(RoughGlass, IsTheDielectricWalksFirstOrder) {
    struct Case {
        double alpha, eta, theta;
    };
    const size_t m = 1000000;
    for (const Case& c : {Case{0.1, 1.5, 30}, Case{0.3, 1.5, 45}, Case{0.6, 1.5, 30}, Case{1.0, 1.5, 45},
                          Case{0.3, 1 / 1.5, 30}, Case{0.6, 1 / 1.5, 20}}) {
        const DielectricMicrosurface s{c.alpha, c.alpha, c.eta};
        const D3 wo = polar(c.theta, 0);
        std::vector<double> walk(2 * Lobe::nu * Lobe::nphi), walk_single(walk.size()), model(walk.size());
        auto cell = [](D3 w) {
            double phi = std::atan2(w.y, w.x);
            if (phi < 0) phi += 2 * M_PI;
            const int a = std::clamp(int((w.z + 1) / 2 * 2 * Lobe::nu), 0, 2 * Lobe::nu - 1);
            return size_t(a * Lobe::nphi + std::min(Lobe::nphi - 1, int(phi / (2 * M_PI) * Lobe::nphi)));
        };
        std::mt19937_64 rng(62);
        for (size_t i = 0; i < m; ++i) {
            D3 out;
            const int bounces = s.walk(wo, rng, &out);
            walk[cell(out)] += 1.0 / double(m);
            if (bounces == 1) walk_single[cell(out)] += 1.0 / double(m);
        }
        const D3 n = float_normal(), t = kernel_tangent(n), b = cross(n, t);
        Params p;
        p.base = {1, 1, 1}, p.dielectric = 0, p.glass = 1, p.eta = c.eta, p.alpha = c.alpha;
        const D3 w = t * wo.x + b * wo.y + n * wo.z;
        const std::vector<float> smp = model_sample(p, n, {float(w.x), float(w.y), float(w.z)}, m, kGlass, 77);
        for (size_t i = 0; i < m; ++i) {
            if (!(int(smp[8 * i + 7]) & 1)) continue;
            const D3 wi = d3(&smp[8 * i]);
            model[cell({dot(wi, t), dot(wi, b), dot(wi, n)})] += smp[8 * i + 4] / double(m);
        }
        double total = 0, single = 0, err = 0, err_all = 0, below = 0, below_single = 0;
        for (size_t k = 0; k < walk.size(); ++k) {
            total += model[k], single += walk_single[k];
            if (k < walk.size() / 2) below += model[k], below_single += walk_single[k];
            err += std::fabs(model[k] - walk_single[k]), err_all += std::fabs(model[k] - walk[k]);
        }
        std::printf("glass alpha %.2f eta %.3f view %g: walk's first order %.4f (transmitted %.4f), model %.4f "
                    "(%.4f), L1 against it %.4f (against the whole walk %.3f)\n",
                    c.alpha, c.eta, c.theta, single, below_single, total, below, err, err_all);
        // Measured L1 0.006 to 0.014, totals within 0.0015, up to alpha 0.6. At alpha 1 the lobe
        // transmits 0.785 where the walk's first order transmits 0.744 (L1 0.045): the lobe's
        // masking for refraction is reflection's height-correlated 1 / (1 + Lambda(o) + Lambda(i)),
        // where heights seen from both sides give the smaller B(1 + Lambda(o), 1 + Lambda(i)) (Heitz
        // 2014, Sec. 6); pbrt-v4 takes the same form as clppm.
        EXPECT_LT(err, c.alpha < 1 ? 0.03 : 0.06);
        EXPECT_NEAR(total, single, c.alpha < 1 ? 0.005 : 0.05);
    }
}

// The value itself, not only where the energy goes: the white metal's f cos towards a light, at
// chosen pairs of view and light in the plane of incidence and across it, against the walk's
// estimate of the same (its next-event estimation at every vertex, single and multiple orders).
// Measured 0.939 to 1.054 of the walk: Kulla-Conty's term has the right amount and a broad shape,
// where the walk's multiple scattering leans to backscatter (view 20, light 10 at alpha 1: 6%
// under) and to the mirror direction.
TEST(IsotropicMetal, ValueTowardsALightMatchesTheWalk) {
    struct Case {
        double alpha, tv, pv, tl, pl; // view and light, (theta, phi) in degrees
    };
    const D3 n = float_normal(), t = kernel_tangent(n), b = cross(n, t);
    for (const Case& c :
         {Case{0.25, 30, 0, 40, 180}, Case{0.5, 30, 0, 45, 180}, Case{0.5, 30, 0, 45, 90}, Case{0.5, 60, 0, 20, 0},
          Case{1.0, 30, 0, 45, 180}, Case{1.0, 45, 0, 70, 90}, Case{1.0, 20, 0, 10, 0}, Case{0.5, 70, 0, 70, 180}}) {
        const Microsurface s{c.alpha, c.alpha, 1};
        const D3 v = polar(c.tv, c.pv), l = polar(c.tl, c.pl);
        std::mt19937_64 rng(9);
        double single = 0, multiple = 0;
        const int m = 400000;
        for (int k = 0; k < m; ++k) s.eval(v, l, rng, &single, &multiple);
        const double walk = (single + multiple) / m;
        Params p;
        p.base = {1, 1, 1}, p.dielectric = 0, p.metal = 1, p.alpha = c.alpha;
        std::vector<float> wi;
        push3(wi, t * l.x + b * l.y + n * l.z);
        const D3 wo = t * v.x + b * v.y + n * v.z;
        const double model = model_eval(p, n, {float(wo.x), float(wo.y), float(wo.z)}, wi, kMetal)[0] * l.z;
        std::printf("alpha %.2f view (%g, %g) light (%g, %g): walk %.4f (multiple %.4f), model %.4f, ratio %.3f\n",
                    c.alpha, c.tv, c.pv, c.tl, c.pl, walk, multiple / m, model, model / walk);
        EXPECT_NEAR(model / walk, 1.0, 0.08);
    }
}

// A white metal sphere under bench/key_fill_lights.py's key and fill (seen from far along +z): the
// image's total, sum over the sphere's pixels of E f cos towards each light, by the kernels' model
// against the walk; stretched spheres with the grooves around the vertical axis, as a UV sphere's
// tangents run. Where Cycles renders the same spheres 4-6% darker than clppm at roughness 0.5 to
// 1 (bench/RESULTS.md), this says where the ground truth lies: round, measured 1.002, 1.036 and
// 1.002 of the walk's at alpha 0.04, 0.25 and 1 (Cycles' sphere about 0.97 and 0.96 of it at 0.25
// and 1); stretched, 1.028 and 1.024 at alpha 0.111 and 0.25 along 1, 0.992 at 0.25 along 0.6.
TEST(MetalSphere, UnderAKeyAndAFillMatchesTheWalk) {
    struct Case {
        double alpha, alpha_t, tolerance;
    };
    const D3 key = normalized({-0.6, 0.5, 0.7}), fill = normalized({0.7, 0.2, 0.6}); // towards the lights
    const D3 v{0, 0, 1};
    const D3 n0 = float_normal(), t0 = kernel_tangent(n0), b0 = cross(n0, t0);
    for (const Case& c : {Case{0.04, 0.04, 0.01}, Case{0.25, 0.25, 0.05}, Case{1.0, 1.0, 0.01}, Case{0.111, 1.0, 0.05},
                          Case{0.25, 1.0, 0.05}, Case{0.25, 0.6, 0.05}}) {
        const Microsurface s{c.alpha_t, c.alpha, 1};
        Params p;
        p.base = {1, 1, 1}, p.dielectric = 0, p.metal = 1, p.alpha = c.alpha;
        if (c.alpha_t != c.alpha) p.alpha_t = c.alpha_t;
        std::mt19937_64 rng(3);
        double walk = 0, model = 0;
        const int grid = 24, walks = 3000;
        for (int y = 0; y < grid; ++y)
            for (int x = 0; x < grid; ++x) {
                const double px = (x + 0.5) / grid * 2 - 1, py = (y + 0.5) / grid * 2 - 1, r2 = px * px + py * py;
                if (r2 >= 1) continue;
                const D3 n{px, py, std::sqrt(1 - r2)};
                const D3 t = normalized(cross(D3{0, 1, 0}, n)), b = cross(n, t); // around the vertical
                auto local = [&](D3 w) { return D3{dot(w, t), dot(w, b), dot(w, n)}; };
                const D3 vl = local(v);
                const D3 wo = t0 * vl.x + b0 * vl.y + n0 * vl.z;
                for (auto [l, e] : {std::pair{key, 3.0}, std::pair{fill, 1.0}}) {
                    const D3 ll = local(l);
                    if (ll.z <= 0) continue;
                    double single = 0, multiple = 0;
                    for (int k = 0; k < walks; ++k) s.eval(vl, ll, rng, &single, &multiple);
                    walk += e * (single + multiple) / walks;
                    std::vector<float> wi;
                    push3(wi, t0 * ll.x + b0 * ll.y + n0 * ll.z);
                    model += e * model_eval(p, n0, {float(wo.x), float(wo.y), float(wo.z)}, wi, kMetal)[0] * ll.z;
                }
            }
        std::printf("alpha %.3f alpha_t %.2f: model / walk %.4f\n", c.alpha, c.alpha_t, model / walk);
        EXPECT_NEAR(model / walk, 1.0, c.tolerance);
    }
}
