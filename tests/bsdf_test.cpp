// kernels/bsdf.cl and the Lambertian branch of kernels/hitpoint.cl on the device against host
// references in double: Fresnel's closed forms (normal incidence, grazing, Brewster's angle,
// total internal reflection) and Hecht's sine/tangent form everywhere else, Snell's law for
// refract_dir, and the Lambertian BRDF's albedo. The GGX lobe is tested in ggx_test.cpp.
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

// Closed forms: ((eta - 1) / (eta + 1))^2 at normal incidence; 1 at grazing incidence; at
// Brewster's angle (tan theta = eta) the p term vanishes and F = rs^2 / 2 with
// rs = (1 - eta^2) / (1 + eta^2); exactly 1 beyond the critical angle. Tolerance 1e-6: float
// arithmetic on O(1) values.
TEST(Bsdf, FresnelDielectricClosedForms) {
    const Device& d = device();
    const double etas[] = {1.0, 1.1, 1.33, 1.5, 2.4, 1 / 1.33, 1 / 1.5, 1 / 2.4};
    std::vector<float> in;
    for (double eta : etas) in.insert(in.end(), {1.0f, float(eta), 0.0f, float(eta)});
    for (double eta : etas) in.insert(in.end(), {float(1 / std::sqrt(1 + eta * eta)), float(eta)});
    std::vector<float> f = d.fresnel(in);
    const size_t ne = std::size(etas);
    for (size_t i = 0; i < ne; ++i) {
        double eta = double(float(etas[i]));
        double r0 = (eta - 1) / (eta + 1);
        EXPECT_NEAR(f[2 * i], r0 * r0, 1e-6) << "normal incidence, eta " << eta;
        // (eta = 1 has no interface; its grazing limit is a 0/0 the kernel may resolve either way.)
        if (eta != 1.0) {
            EXPECT_NEAR(f[2 * i + 1], 1.0, 1e-6) << "grazing incidence, eta " << eta;
        }
        double rs = (1 - eta * eta) / (1 + eta * eta);
        EXPECT_NEAR(f[2 * ne + i], rs * rs / 2, 1e-6) << "Brewster's angle, eta " << eta;
    }
    // Total internal reflection from inside glass (eta = 1/1.5): every cos_i below the critical
    // cos sqrt(1 - eta^2) = 0.745 reflects everything; just above it the value drops below 1.
    std::vector<float> tir;
    const double eta = 1 / 1.5, cos_c = std::sqrt(1 - eta * eta);
    for (int k = 0; k <= 100; ++k) tir.insert(tir.end(), {float(cos_c * k / 100.0 * 0.9999), float(eta)});
    tir.insert(tir.end(), {float(cos_c + 1e-3), float(eta)});
    std::vector<float> ft = d.fresnel(tir);
    for (int k = 0; k <= 100; ++k) EXPECT_EQ(ft[k], 1.0f) << "cos_i " << tir[2 * k];
    EXPECT_LT(ft[101], 1.0f);
    EXPECT_GT(ft[101], 0.5f) << "continuous at the critical angle";
}

// Everywhere else: against Hecht's sine/tangent form over cos_i in (0.001, 1) for each eta, and
// always within [0, 1] even for cos_i slightly outside [0, 1]. Tolerance: 2e-6 absolute (float
// arithmetic on O(1) values) plus how much the exact F moves when cos_i and eta move by 4 float
// ulps: near the critical angle F has an infinite slope in cos_i, and no float evaluation can do
// better than its inputs' rounding there.
TEST(Bsdf, FresnelDielectricMatchesHechtEverywhere) {
    const Device& d = device();
    std::vector<float> in;
    const double etas[] = {1.05, 1.33, 1.5, 2.4, 1 / 1.05, 1 / 1.33, 1 / 1.5, 1 / 2.4};
    for (double eta : etas)
        for (int k = 1; k < 1000; ++k) in.insert(in.end(), {float(k / 1000.0), float(eta)});
    std::vector<float> f = d.fresnel(in);
    double worst = 0;
    for (size_t i = 0; i < f.size(); ++i) {
        double c = in[2 * i], e = in[2 * i + 1], ref = ref_fresnel_hecht(c, e), moved = 0;
        for (double dc : {-4.8e-7, 0.0, 4.8e-7})
            for (double de : {-4.8e-7, 0.0, 4.8e-7})
                moved = std::max(moved, std::fabs(ref_fresnel_hecht(std::min(1.0, c * (1 + dc)), e * (1 + de)) - ref));
        worst = std::max(worst, std::fabs(f[i] - ref) / (2e-6 + moved));
        ASSERT_NEAR(f[i], ref, 2e-6 + moved) << "cos_i " << c << " eta " << e;
    }
    std::vector<float> odd = {-1e-7f, 1.5f, -0.5f, 1.5f, 1.0000001f, 1.5f, 2.0f, 1.0f / 1.5f, -1.0f, 1.0f / 1.5f};
    for (float v : d.fresnel(odd)) EXPECT_TRUE(v >= 0.0f && v <= 1.0f) << v;
}

// refract_dir: unit, through the surface, in the plane of incidence, eta sin_t = sin_i, and
// reversible (refracting back with 1/eta returns -d). Random incident directions below the
// critical angle for several eta and random normals. Tolerance 2e-6: float directions.
TEST(Bsdf, RefractSatisfiesSnellsLaw) {
    const Device& d = device();
    std::mt19937_64 g(21);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> uni(0, 1);
    std::vector<float> dirs, normals, etas;
    const double eta_set[] = {1.0, 1.33, 1.5, 2.4, 1 / 1.33, 1 / 1.5, 1 / 2.4};
    for (int i = 0; i < 20000; ++i) {
        D3 n = normalized({gauss(g), gauss(g), gauss(g)});
        double eta = eta_set[i % std::size(eta_set)];
        // sin_i up to the critical sine (eta < 1) or 1, minus a margin.
        double max_sin = std::min(1.0, eta) * 0.9999, sin_i = max_sin * std::sqrt(uni(g)),
               cos_i = std::sqrt(1 - sin_i * sin_i);
        D3 t, b;
        host_frame(n, t, b);
        double phi = 2 * M_PI * uni(g);
        D3 dir =
            normalized((sin_i * std::cos(phi)) * t + (sin_i * std::sin(phi)) * b - cos_i * n); // towards the surface
        push3(dirs, dir), push3(normals, n), etas.push_back(float(eta));
    }
    const size_t m = etas.size();
    auto refract = [&](const std::vector<float>& dv, const std::vector<float>& nv, const std::vector<float>& ev) {
        cl::Buffer db = d.input(dv), nb = d.input(nv), eb = d.input(ev), out = d.output(3 * m * sizeof(float));
        cl::Kernel k(d.program, "refract");
        k.setArg(0, db), k.setArg(1, nb), k.setArg(2, eb), k.setArg(3, out);
        d.run(k, m);
        return d.read<float>(out, 3 * m);
    };
    std::vector<float> tr = refract(dirs, normals, etas);
    std::vector<float> back_d, back_n, back_e;
    for (size_t i = 0; i < m; ++i) {
        D3 dir = at3(dirs, i), n = at3(normals, i), t = at3(tr, i);
        double eta = etas[i];
        ASSERT_NEAR(length(t), 1.0, 2e-6);
        ASSERT_LT(dot(t, n), 0.0) << "the refracted ray continues through the surface";
        D3 plane = cross(dir, n);
        ASSERT_LT(std::fabs(dot(t, plane)), 2e-6) << "out of the plane of incidence";
        double sin_i = length(cross(dir, n)), sin_t = length(cross(t, n));
        ASSERT_NEAR(eta * sin_t, sin_i, 2e-6 * std::max(1.0, eta)) << "Snell, eta " << eta;
        // The reverse path: light along -t meets the surface from the other side (normal -n).
        push3(back_d, -1.0 * t), push3(back_n, -1.0 * n), back_e.push_back(float(1.0 / eta));
    }
    std::vector<float> back = refract(back_d, back_n, back_e);
    double worst = 0;
    for (size_t i = 0; i < m; ++i) worst = std::max(worst, length(at3(back, i) + at3(dirs, i)));
    // Back and forth through float: directions within 1e-5 unless near the critical angle, where
    // cos_t -> 0 amplifies rounding; the margin 0.9999 on sin keeps cos_t >= 0.014.
    EXPECT_LT(worst, 2e-4);
    // Normal incidence passes straight through for any eta.
    std::vector<float> nd = {0, 0, -1}, nn = {0, 0, 1}, ne = {1.5f};
    cl::Buffer db = d.input(nd), nb = d.input(nn), eb = d.input(ne), out = d.output(3 * sizeof(float));
    cl::Kernel k(d.program, "refract");
    k.setArg(0, db), k.setArg(1, nb), k.setArg(2, eb), k.setArg(3, out);
    d.run(k, 1);
    std::vector<float> s = d.read<float>(out, 3);
    EXPECT_NEAR(s[2], -1.0, 1e-7);
}

// The Lambertian branch of hitpoint_brdf: f = albedo / pi above the surface, 0 below, so that the
// integral of f cos over the hemisphere is the albedo (Gauss-Legendre in (cos theta, phi), exact
// for this integrand up to float).
TEST(Bsdf, LambertianAlbedoOverPiIntegratesToAlbedo) {
    const Device& d = device();
    const D3 n = float_normal();
    D3 t, b;
    host_frame(n, t, b);
    for (float rho : {0.0f, 0.25f, 0.8f, 1.0f}) {
        dev::HitPoint hp{};
        hp.color[0] = hp.color[1] = hp.color[2] = rho;
        hp.alpha = 1;
        hp.dielectric = 1; // no specular layer (f0 = f90 = 0): plain Lambertian
        std::vector<float> wi;
        std::vector<double> wts;
        const int nc = 32, np = 32;
        for (int i = 0; i < nc; ++i)
            for (int j = 0; j < np; ++j)
                for (int a = 0; a < 4; ++a)
                    for (int c = 0; c < 4; ++c) {
                        double ct = -1 + 2.0 * (i + kGlX[a]) / nc, phi = 2 * M_PI * (j + kGlX[c]) / np;
                        double st = std::sqrt(1 - ct * ct);
                        push3(wi, (st * std::cos(phi)) * t + (st * std::sin(phi)) * b + ct * n);
                        wts.push_back(kGlW[a] * kGlW[c] * (2.0 / nc) * (2 * M_PI / np) * std::max(0.0, ct));
                    }
        const size_t m = wts.size();
        cl::Buffer hb = d.input(std::vector<dev::HitPoint>{hp}), ib = d.input(wi), out = d.output(m * sizeof(float));
        cl::Kernel k(d.program, "lambert");
        k.setArg(0, hb), k.setArg(1, float(n.x)), k.setArg(2, float(n.y)), k.setArg(3, float(n.z)), k.setArg(4, ib),
            k.setArg(5, out);
        d.run(k, m);
        std::vector<float> f = d.read<float>(out, m);
        double albedo = 0;
        for (size_t i = 0; i < m; ++i) {
            albedo += f[i] * wts[i];
            if (dot(at3(wi, i), n) < -1e-6) {
                ASSERT_EQ(f[i], 0.0f) << "no light from below";
            }
        }
        EXPECT_NEAR(albedo, rho, 1e-5) << "rho " << rho;
    }
}
