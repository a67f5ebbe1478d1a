// kernels/ggx.cl on the device against host references in double: the GGX D/G2/Schlick model
// written out from Walter et al. 2007 and Heitz 2014, the VNDF sampler's histogram against
// ggx_pdf (chi-square), the sample weight against eval cos / pdf, reciprocity, energy
// conservation, and finite values at the extremes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bsdf_kernels.h"
#include "shared_types.h"
#include "stat_tests.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;
using namespace clppm::test::bsdf;

// ggx_eval and ggx_pdf against the double reference at random (wo, wi), including wi below the
// surface (both 0). Compared where both cosines exceed 1e-5: ggx_lambda clamps cos^2 at 1e-12 on
// purpose (no division by zero), which changes Lambda below cos 1e-6 (values there are checked
// for finiteness in Ggx.AtExtremesStaysFinite). Tolerance: relative 3e-3 of the value plus 1e-6
// of the lobe's peak. Float
// cancellation in D's t = cos_h^2 (alpha^2 - 1) + 1 near the peak costs 6e-8 / alpha^2 relative
// (2.4e-5 at alpha 0.05), and cos_h from a float half vector (1e-7 absolute) moves D by
// 4e-7 / alpha^2 relative there (1.6e-4): 3e-3 covers alpha >= 0.05 with margin.
TEST(Ggx, EvalAndPdfMatchReference) {
    std::mt19937_64 g(22);
    std::normal_distribution<double> gauss;
    const D3 n = float_normal();
    for (double alpha : kAlphas)
        for (double f0 : {1.0, 0.04}) {
            std::vector<float> wo, wi;
            for (int i = 0; i < 50000; ++i) {
                D3 a = normalized({gauss(g), gauss(g), gauss(g)}), b = normalized({gauss(g), gauss(g), gauss(g)});
                if (dot(a, n) < 0) a = -1.0 * a;
                if (i % 4 != 0 && dot(b, n) < 0) b = -1.0 * b; // a quarter may lie below
                if (i % 3 == 0)
                    b = normalized((2 * dot(a, n)) * n - a + (0.3 * alpha * gauss(g)) * D3{1, 0, 0}); // near the peak
                push3(wo, a), push3(wi, b);
            }
            const Device& d = device();
            const size_t m = wi.size() / 3;
            cl::Buffer ob = d.input(wo), ib = d.input(wi), out = d.output(2 * m * sizeof(float));
            cl::Kernel k(d.program, "ggx_eval_pdf");
            k.setArg(0, float(n.x)), k.setArg(1, float(n.y)), k.setArg(2, float(n.z)), k.setArg(3, float(f0));
            k.setArg(4, float(alpha)), k.setArg(5, ob), k.setArg(6, ib), k.setArg(7, cl_uint(1)), k.setArg(8, out);
            d.run(k, m);
            std::vector<float> v = d.read<float>(out, 2 * m);
            const double peak = ref_d(1, alpha); // D's maximum bounds both values' scale
            double worst_eval = 0, worst_pdf = 0;
            for (size_t i = 0; i < m; ++i) {
                D3 a = at3(wo, i), b = at3(wi, i);
                double re = ref_eval(n, a, b, f0, alpha), rp = ref_pdf(n, a, b, alpha);
                double se = 3e-3 * re + 1e-6 * peak / std::max(1e-3, 4 * dot(n, a) * std::fabs(dot(n, b)));
                double sp = 3e-3 * rp + 1e-6 * peak / std::max(1e-3, 4 * dot(n, a));
                ASSERT_TRUE(std::isfinite(v[2 * i]) && std::isfinite(v[2 * i + 1]));
                if (dot(n, a) < 1e-5 || std::fabs(dot(n, b)) < 1e-5) continue;
                worst_eval = std::max(worst_eval, std::fabs(v[2 * i] - re) / se);
                worst_pdf = std::max(worst_pdf, std::fabs(v[2 * i + 1] - rp) / sp);
                if (dot(n, b) <= 0) {
                    ASSERT_EQ(v[2 * i], 0.0f);
                    ASSERT_EQ(v[2 * i + 1], 0.0f);
                }
            }
            EXPECT_LE(worst_eval, 1.0) << "alpha " << alpha << " f0 " << f0 << ": eval error / tolerance";
            EXPECT_LE(worst_pdf, 1.0) << "alpha " << alpha << ": pdf error / tolerance";
        }
}

// Reciprocity f(wo, wi) = f(wi, wo): the same arithmetic in a different order, so relative 1e-5.
TEST(Ggx, EvalIsReciprocal) {
    std::mt19937_64 g(23);
    std::normal_distribution<double> gauss;
    const D3 n = float_normal();
    for (double alpha : kAlphas) {
        std::vector<float> a, b;
        for (int i = 0; i < 20000; ++i) {
            D3 x = normalized({gauss(g), gauss(g), gauss(g)}), y = normalized({gauss(g), gauss(g), gauss(g)});
            if (dot(x, n) < 0) x = -1.0 * x;
            if (dot(y, n) < 0) y = -1.0 * y;
            push3(a, x), push3(b, y);
        }
        const Device& d = device();
        const size_t m = a.size() / 3;
        auto eval = [&](const std::vector<float>& wo, const std::vector<float>& wi) {
            cl::Buffer ob = d.input(wo), ib = d.input(wi), out = d.output(2 * m * sizeof(float));
            cl::Kernel k(d.program, "ggx_eval_pdf");
            k.setArg(0, float(n.x)), k.setArg(1, float(n.y)), k.setArg(2, float(n.z)), k.setArg(3, 0.5f);
            k.setArg(4, float(alpha)), k.setArg(5, ob), k.setArg(6, ib), k.setArg(7, cl_uint(1)), k.setArg(8, out);
            d.run(k, m);
            return d.read<float>(out, 2 * m);
        };
        std::vector<float> f1 = eval(a, b), f2 = eval(b, a);
        for (size_t i = 0; i < m; ++i)
            ASSERT_NEAR(f1[2 * i], f2[2 * i], 1e-5 * std::fabs(f1[2 * i]) + 1e-30) << "alpha " << alpha;
    }
}

// ggx_pdf over the hemisphere of wi integrates to the probability that ggx_sample returns a wi
// above the surface (1 at normal incidence, less where reflected microfacet normals send wi
// below): quadrature of the device pdf in half-vector space against the fraction of 250k
// device samples above the surface. Tolerance: 5 binomial sigma (<= 5e-3 at p = 0.5, much less
// near 1) plus 3e-3 for the quadrature (64 x 64 cells of 4 x 4 Gauss-Legendre nodes, refined
// where the horizon cuts through a cell; measured within 1e-3 of the closed form at normal
// incidence).
TEST(Ggx, PdfIntegratesToTheSampledFraction) {
    const D3 n = float_normal();
    for (double alpha : kAlphas)
        for (double cos_o : kViews) {
            D3 wo = view(cos_o);
            HalfVectorGrid grid(n, wo, alpha);
            Quadrature q = half_vector_quadrature(grid, 64, 64);
            std::vector<float> v = device_eval_pdf(n, wo, 1.0, alpha, q.wi);
            double integral = 0;
            for (size_t i = 0; i < q.weight.size(); ++i) integral += v[2 * i + 1] * q.weight[i];
            const size_t m = 250000;
            std::vector<float> s = device_samples(n, wo, 1.0, alpha, uniforms(2 * m, 31));
            double above = 0;
            for (size_t i = 0; i < m; ++i) above += dot(at3(s, 2 * i), n) > 0; // at3 of 6-float records: index 2i
            above /= m;
            EXPECT_LE(integral, 1.0 + 1e-3) << "alpha " << alpha << " cos_o " << cos_o;
            EXPECT_NEAR(integral, above, 3e-3 + 5 * std::sqrt(above * (1 - above) / m))
                << "alpha " << alpha << " cos_o " << cos_o;
            // At normal incidence the visible normals are D cos, and wi = reflect(n, h) stays above
            // the surface for theta_h < 45 degrees: u < 1 / (1 + alpha^2) in HalfVectorGrid's terms.
            if (cos_o == 1.0) {
                EXPECT_NEAR(integral, 1 / (1 + alpha * alpha), 2e-3) << "alpha " << alpha;
            }
        }
}

// ggx_sample's histogram against ggx_pdf integrated per bin (Pearson chi-square; pbrt-v4's
// microfacet tests). Bins in the half vector's (u, phi) coordinates (HalfVectorGrid: 16 x 32),
// equivalent to bins over wi but adapted to the lobe's width, plus one bin for samples that fall
// below the surface, which expects the pdf's missing mass.
TEST(Ggx, SampleMatchesPdfChiSquare) {
    const D3 n = float_normal();
    const double alpha_level = sidak(1e-3, 12);
    const int nu = 16, nphi = 32;
    for (double alpha : kAlphas)
        for (double cos_o : kViews) {
            D3 wo = view(cos_o);
            HalfVectorGrid grid(n, wo, alpha);
            Quadrature q = half_vector_quadrature(grid, 2 * nu, 2 * nphi); // 2 x 2 quadrature cells per bin
            std::vector<float> v = device_eval_pdf(n, wo, 1.0, alpha, q.wi);
            const size_t m = 300000;
            std::vector<double> expected = expected_bin_counts(q, v, 2, 1, nu, nphi, 2, m);
            std::vector<double> observed(nu * nphi + 1, 0);
            std::vector<float> s =
                device_samples(n, wo, 1.0, alpha, uniforms(2 * m, 32 + uint64_t(alpha * 100 + cos_o * 10)));
            for (size_t i = 0; i < m; ++i) {
                D3 wi = at3(s, 2 * i);
                if (dot(wi, n) <= 0) {
                    observed[nu * nphi] += 1;
                    continue;
                }
                double u, phi;
                grid.coords(wi, &u, &phi);
                int bu = std::min(nu - 1, int(u * nu)), bp = std::min(nphi - 1, int(phi / (2 * M_PI) * nphi));
                observed[bu * nphi + bp] += 1;
            }
            Chi2Result c = chi2_test(observed, expected);
            EXPECT_TRUE(c.error.empty()) << "alpha " << alpha << " cos_o " << cos_o << ": " << c.error;
            EXPECT_GT(c.p_value, alpha_level)
                << "alpha " << alpha << " cos_o " << cos_o << ": chi2 " << c.chi2 << " dof " << c.dof;
        }
}

// The sample weight is f cos / pdf at the sampled direction (so estimators that use the weight
// and those that use eval and pdf agree), and is zero exactly when wi is below the surface.
// Relative 2e-4: eval and pdf recompute h from the float wi, and D cancels between them.
TEST(Ggx, SampleWeightIsEvalCosOverPdf) {
    const D3 n = float_normal();
    for (double alpha : kAlphas)
        for (double cos_o : kViews)
            for (double f0 : {1.0, 0.3}) {
                const size_t m = 50000;
                std::vector<float> s = device_samples(n, view(cos_o), f0, alpha, uniforms(2 * m, 41));
                double worst = 0;
                for (size_t i = 0; i < m; ++i) {
                    const float* r = &s[6 * i];
                    ASSERT_TRUE(std::isfinite(r[3])) << "alpha " << alpha;
                    if (dot(D3{r[0], r[1], r[2]}, n) <= 0) {
                        ASSERT_EQ(r[3], 0.0f);
                        continue;
                    }
                    ASSERT_GT(r[5], 0.0f) << "a sampled direction must have positive pdf";
                    double ratio = double(r[4]) / r[5];
                    worst = std::max(worst, std::fabs(r[3] - ratio) / std::max(1e-6, ratio));
                }
                EXPECT_LT(worst, 2e-4) << "alpha " << alpha << " cos_o " << cos_o << " f0 " << f0;
            }
}

// Energy conservation: with F0 = 1 the directional albedo, the integral of f cos over wi, stays
// at most 1 (single-scattering GGX loses energy, never gains it) for every alpha and view; the
// device quadrature and the mean sample weight (Monte Carlo, 5 sigma) agree, and both match the
// same integral of the host reference to 2e-3.
TEST(Ggx, AlbedoIsAtMostOne) {
    const D3 n = float_normal();
    for (double alpha : {0.05, 0.2, 0.6, 1.0})
        for (double cos_o : {1.0, 0.7, 0.2, 0.05}) {
            D3 wo = view(cos_o);
            HalfVectorGrid grid(n, wo, alpha);
            Quadrature q = half_vector_quadrature(grid, 64, 64);
            std::vector<float> v = device_eval_pdf(n, wo, 1.0, alpha, q.wi);
            double albedo = 0, ref = 0;
            for (size_t i = 0; i < q.weight.size(); ++i) {
                D3 wi = at3(q.wi, i);
                double c = std::max(0.0, dot(n, wi));
                albedo += v[2 * i] * c * q.weight[i];
                ref += ref_eval(n, wo, wi, 1.0, alpha) * c * q.weight[i];
            }
            const size_t m = 100000;
            std::vector<float> s = device_samples(n, wo, 1.0, alpha, uniforms(2 * m, 51));
            std::vector<double> w(m);
            for (size_t i = 0; i < m; ++i) w[i] = s[6 * i + 3];
            MeanSe mc = mean_se(w);
            EXPECT_LE(albedo, 1.0 + 1e-3) << "alpha " << alpha << " cos_o " << cos_o;
            EXPECT_LE(mc.mean, 1.0) << "alpha " << alpha << " cos_o " << cos_o;
            EXPECT_NEAR(albedo, ref, 2e-3) << "alpha " << alpha << " cos_o " << cos_o;
            EXPECT_NEAR(mc.mean, albedo, 5 * mc.se + 2e-3) << "alpha " << alpha << " cos_o " << cos_o;
            for (double x : w) ASSERT_TRUE(x >= 0 && x <= 1.0 + 1e-6) << "F0 = 1: the weight G2/G1 lies in [0, 1]";
            if (alpha == 0.05) {
                EXPECT_GT(albedo, cos_o >= 0.2 ? 0.95 : 0.8) << "a smooth conductor reflects nearly all";
            }
        }
}

// At the extremes: alpha at material_alpha's floor (1e-4) and 1, views down to 1e-7 from grazing,
// u at 0 and 1 - 2^-24: wi finite and unit, weight finite in [0, 1] for F0 = 1 (the path tracer,
// photon tracer and eye pass sample every glossy surface this way); eval and pdf finite and
// non-negative for alpha >= 1e-3 (see Ggx.EvalAndPdfFiniteAtMaterialAlphaFloor for 1e-4).
TEST(Ggx, AtExtremesStaysFinite) {
    const D3 n = float_normal();
    const float top = 1.0f - 1.0f / 16777216.0f;
    std::vector<float> u;
    for (float a : {0.0f, 1e-7f, 0.5f, top})
        for (float b : {0.0f, 0.5f, top}) u.push_back(a), u.push_back(b);
    for (double alpha : {1e-4, 1e-3, 0.04, 1.0})
        for (double cos_o : {1.0, 0.5, 1e-3, 1e-5, 1e-7}) {
            std::vector<float> s = device_samples(n, view(cos_o), 1.0, alpha, u);
            for (size_t i = 0; i < u.size() / 2; ++i) {
                const float* r = &s[6 * i];
                std::string what = "alpha " + std::to_string(alpha) + " cos_o " + std::to_string(cos_o) + " u " +
                                   std::to_string(u[2 * i]) + "," + std::to_string(u[2 * i + 1]);
                for (int k = 0; k < (alpha >= 1e-3 ? 6 : 4); ++k)
                    ASSERT_TRUE(std::isfinite(r[k])) << what << " value " << k;
                EXPECT_NEAR(length(D3{r[0], r[1], r[2]}), 1.0, 1e-5) << what;
                EXPECT_GE(r[3], 0.0f) << what;
                EXPECT_LE(r[3], 1.0f + 1e-6f) << what;
                EXPECT_GE(r[4], 0.0f) << what;
                EXPECT_GE(r[5], 0.0f) << what;
            }
        }
}

// material_alpha floors alpha at 1e-4, so 1e-4 is a valid GGX alpha; D there peaks at
// 1 / (pi alpha^2) = 3.2e7, well inside float range. ggx_eval and ggx_pdf must stay finite at and
// near the mirror direction. (Today only alpha >= GLOSSY_HITPOINT_ALPHA reaches ggx_eval/ggx_pdf
// in the renderer; smoother surfaces are only sampled, and the sample weight does not involve D.)
// This test found ggx_d evaluating t = cos^2 (alpha^2 - 1) + 1, which cancels in float (alpha^2 - 1
// rounds to -1 for alpha < 1.7e-4, so t = 0 and D = +inf at cos_h = 1); it now computes
// t = (1 - cos^2) + cos^2 alpha^2.
TEST(Ggx, EvalAndPdfFiniteAtMaterialAlphaFloor) {
    const D3 n{0, 0, 1};
    for (double alpha : {1e-4, 2e-4, 5e-4})
        for (double cos_o : {1.0, 0.6}) {
            D3 wo{std::sqrt(1 - cos_o * cos_o), 0, cos_o};
            std::vector<float> wi;
            push3(wi, D3{-wo.x, 0, wo.z}); // the mirror direction: h = n
            for (double e : {1e-5, 1e-4, 1e-3}) push3(wi, normalized(D3{-wo.x + e, e, wo.z}));
            std::vector<float> v = device_eval_pdf(n, wo, 1.0, alpha, wi);
            for (size_t i = 0; i < wi.size() / 3; ++i) {
                EXPECT_TRUE(std::isfinite(v[2 * i]))
                    << "ggx_eval, alpha " << alpha << " cos_o " << cos_o << " wi " << i << ": " << v[2 * i];
                EXPECT_TRUE(std::isfinite(v[2 * i + 1]))
                    << "ggx_pdf, alpha " << alpha << " cos_o " << cos_o << " wi " << i << ": " << v[2 * i + 1];
            }
        }
}
