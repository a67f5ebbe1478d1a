// kernels/bsdf.cl, kernels/ggx.cl and the Lambertian branch of kernels/hitpoint.cl on the device
// against host references in double: Fresnel's closed forms (normal incidence, grazing,
// Brewster's angle, total internal reflection) and Hecht's sine/tangent form everywhere else,
// Snell's law for refract_dir, the GGX D/G2/Schlick model written out from Walter et al. 2007
// and Heitz 2014, the VNDF sampler's histogram against ggx_pdf (chi-square), the sample weight
// against eval cos / pdf, reciprocity, energy conservation, and finite values at the extremes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "device/kernel_program.h"
#include "shared_types.h"
#include "stat_tests.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

const char* kWrappers = R"CL(
__kernel void fresnel(__global const float* cos_eta, __global float* out) {
    uint i = get_global_id(0);
    out[i] = fresnel_dielectric(cos_eta[2 * i], cos_eta[2 * i + 1]);
}
__kernel void refract(__global const float* d, __global const float* n, __global const float* eta,
                      __global float* out) {
    uint i = get_global_id(0);
    float3 t = refract_dir((float3)(d[3 * i], d[3 * i + 1], d[3 * i + 2]),
                           (float3)(n[3 * i], n[3 * i + 1], n[3 * i + 2]), eta[i]);
    out[3 * i] = t.x; out[3 * i + 1] = t.y; out[3 * i + 2] = t.z;
}
/* ggx_eval (F0 grey) and ggx_pdf for pairs (wo[i], wi[i]) about n. */
__kernel void ggx_eval_pdf(float nx, float ny, float nz, float f0, float alpha, __global const float* wo,
                           __global const float* wi, uint wo_stride, __global float* out) {
    uint i = get_global_id(0);
    float3 n = (float3)(nx, ny, nz);
    float3 o = (float3)(wo[3 * i * wo_stride], wo[3 * i * wo_stride + 1], wo[3 * i * wo_stride + 2]);
    float3 w = (float3)(wi[3 * i], wi[3 * i + 1], wi[3 * i + 2]);
    out[2 * i] = ggx_eval(n, o, w, (float3)(f0), alpha).x;
    out[2 * i + 1] = ggx_pdf(n, o, w, alpha);
}
/* ggx_sample from one wo: wi, the weight, and eval cos / pdf at the returned wi. */
__kernel void ggx_sample_many(float nx, float ny, float nz, float ox, float oy, float oz, float f0, float alpha,
                              __global const float* u, __global float* out) {
    uint i = get_global_id(0);
    float3 n = (float3)(nx, ny, nz), wo = (float3)(ox, oy, oz), wi;
    float3 w = ggx_sample(n, wo, (float3)(f0), alpha, u[2 * i], u[2 * i + 1], &wi);
    float pdf = ggx_pdf(n, wo, wi, alpha);
    float3 f = ggx_eval(n, wo, wi, (float3)(f0), alpha);
    __global float* o = &out[6 * i];
    o[0] = wi.x; o[1] = wi.y; o[2] = wi.z; o[3] = w.x;
    o[4] = f.x * fmax(0.0f, dot(n, wi)); o[5] = pdf;
}
/* The Lambertian branch of hitpoint_brdf (alpha 0). */
__kernel void lambert(__global const HitPoint* hp, float nx, float ny, float nz, __global const float* wi,
                      __global float* out) {
    uint i = get_global_id(0);
    out[i] = hitpoint_brdf(hp, (float3)(nx, ny, nz), (float3)(wi[3 * i], wi[3 * i + 1], wi[3 * i + 2])).y;
}
)CL";

struct Device : KernelHarness {
    // Include guards make the second file add only what the first lacked (hitpoint.cl).
    Device() : KernelHarness(assemble_kernel_source("bsdf.cl") + assemble_kernel_source("hitpoint.cl") + kWrappers) {}

    std::vector<float> fresnel(const std::vector<float>& cos_eta) const {
        size_t n = cos_eta.size() / 2;
        cl::Buffer in = input(cos_eta), out = output(n * sizeof(float));
        cl::Kernel k(program, "fresnel");
        k.setArg(0, in), k.setArg(1, out);
        run(k, n);
        return read<float>(out, n);
    }
};

const Device& device() {
    static Device d;
    return d;
}

// ---- host vectors and references ----

void push3(std::vector<float>& v, D3 a) { v.push_back(float(a.x)), v.push_back(float(a.y)), v.push_back(float(a.z)); }
D3 at3(const std::vector<float>& v, size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }

// Fresnel for unpolarised light from the Fresnel equations in Hecht's form (Optics, Eq. 4.42-4.43):
// Rs = sin^2(ti - tt) / sin^2(ti + tt), Rp = tan^2(ti - tt) / tan^2(ti + tt); 1 under TIR.
double ref_fresnel_hecht(double cos_i, double eta) {
    double ti = std::acos(cos_i), s = std::sin(ti) / eta;
    if (s >= 1) return 1;
    double tt = std::asin(s);
    double rs = std::sin(ti - tt) / std::sin(ti + tt), rp = std::tan(ti - tt) / std::tan(ti + tt);
    return 0.5 * (rs * rs + rp * rp);
}

// GGX (Walter et al. 2007, Eq. 33), Smith Lambda (Heitz 2014, Eq. 72), height-correlated G2
// (Heitz 2014, Eq. 99), Schlick's Fresnel.
double ref_d(double c, double a) {
    double t = c * c * (a * a - 1) + 1;
    return a * a / (M_PI * t * t);
}
double ref_lambda(double c, double a) { return 0.5 * (-1 + std::sqrt(1 + a * a * (1 - c * c) / (c * c))); }
double ref_eval(D3 n, D3 wo, D3 wi, double f0, double a) {
    double co = dot(n, wo), ci = dot(n, wi);
    if (co <= 0 || ci <= 0) return 0;
    D3 h = normalized(wo + wi);
    double F = f0 + (1 - f0) * std::pow(1 - dot(wi, h), 5);
    return F * ref_d(dot(n, h), a) / (1 + ref_lambda(co, a) + ref_lambda(ci, a)) / (4 * co * ci);
}
double ref_pdf(D3 n, D3 wo, D3 wi, double a) {
    double co = dot(n, wo), ci = dot(n, wi);
    if (co <= 0 || ci <= 0) return 0;
    D3 h = normalized(wo + wi);
    return ref_d(dot(n, h), a) / (1 + ref_lambda(co, a)) / (4 * co);
}

// Directions wi parameterised by their half vector h about n: tan^2(theta_h) = alpha^2 u / (1 - u)
// makes D(h) cos(theta_h) d omega_h = du dphi / (2 pi), so a grid in (u, phi) is dense where the
// lobe is, whatever alpha. With wi = reflect(wo, h), d omega_i = 4 (wo.h) d omega_h: an integral
// over wi is the sum over (u, phi) of g(wi) * jacobian.
struct HalfVectorGrid {
    D3 n, t, b, wo;
    double alpha;
    HalfVectorGrid(D3 n_, D3 wo_, double a) : n(n_), wo(wo_), alpha(a) { host_frame(n, t, b); }
    // h, and whether it reflects wo to a defined wi (wo.h > 0).
    D3 half(double u, double phi) const {
        double tan2 = alpha * alpha * u / (1 - u), c = 1 / std::sqrt(1 + tan2), s = std::sqrt(std::max(0.0, 1 - c * c));
        return (s * std::cos(phi)) * t + (s * std::sin(phi)) * b + c * n;
    }
    D3 wi(D3 h) const { return (2 * dot(wo, h)) * h - wo; }
    double jacobian(D3 h) const { return 4 * dot(wo, h) / (ref_d(dot(h, n), alpha) * dot(h, n)) / (2 * M_PI); }
    // (u, phi) of a direction wi, for binning samples.
    void coords(D3 wi_, double* u, double* phi) const {
        D3 h = normalized(wo + wi_);
        double c = std::min(1.0, dot(h, n)), s2 = std::max(0.0, 1 - c * c);
        *u = s2 / (s2 + c * c * alpha * alpha);
        *phi = std::atan2(dot(h, b), dot(h, t));
        if (*phi < 0) *phi += 2 * M_PI;
    }
};

// Gauss-Legendre nodes on [0, 1] (4 points) for the quadratures below.
const double kGlX[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
const double kGlW[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};

// Quadrature points over (u, phi) in [0,1] x [0, 2 pi): nu x nphi cells of 4 x 4 Gauss-Legendre
// nodes. The integrands jump to zero where wi crosses the horizon; a cell in which that happens
// (nodes, corners and edge midpoints disagree about wi.n > 0) is split in four, down to `depth`
// levels, so the jump costs 4^-depth of a cell instead of a cell. Returns the wi of every node
// with wo.h > 0, its weight (cell area x jacobian), and the top-level cell it lies in.
struct Quadrature {
    std::vector<float> wi;
    std::vector<double> weight;
    std::vector<int> cell;
};
void quadrature_cell(const HalfVectorGrid& g, double u0, double u1, double p0, double p1, int depth, int id,
                     Quadrature& q) {
    auto above = [&](double u, double phi) {
        D3 h = g.half(u, phi);
        return dot(g.wo, h) > 0 && dot(g.wi(h), g.n) > 0;
    };
    const double du = u1 - u0, dp = p1 - p0;
    if (depth > 0) {
        int count = 0, total = 0;
        for (double a : {0.0, 0.5, 1.0})
            for (double c : {0.0, 0.5, 1.0}) count += above(u0 + a * du, p0 + c * dp), ++total;
        for (int a = 0; a < 4; ++a)
            for (int c = 0; c < 4; ++c) count += above(u0 + kGlX[a] * du, p0 + kGlX[c] * dp), ++total;
        if (count > 0 && count < total) {
            const double um = u0 + 0.5 * du, pm = p0 + 0.5 * dp;
            quadrature_cell(g, u0, um, p0, pm, depth - 1, id, q);
            quadrature_cell(g, um, u1, p0, pm, depth - 1, id, q);
            quadrature_cell(g, u0, um, pm, p1, depth - 1, id, q);
            quadrature_cell(g, um, u1, pm, p1, depth - 1, id, q);
            return;
        }
    }
    for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 4; ++c) {
            double u = u0 + kGlX[a] * du, phi = p0 + kGlX[c] * dp;
            D3 h = g.half(u, phi);
            if (dot(g.wo, h) <= 0) continue;
            push3(q.wi, normalized(g.wi(h)));
            q.weight.push_back(kGlW[a] * kGlW[c] * du * dp * g.jacobian(h));
            q.cell.push_back(id);
        }
}
Quadrature half_vector_quadrature(const HalfVectorGrid& g, int nu, int nphi, int depth = 6) {
    Quadrature q;
    const double du = 1.0 / nu, dp = 2 * M_PI / nphi;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nphi; ++j)
            quadrature_cell(g, i * du, (i + 1) * du, j * dp, (j + 1) * dp, depth, i * nphi + j, q);
    return q;
}

// Device ggx_eval and ggx_pdf at (wo, wi[k]): values interleaved (eval, pdf).
std::vector<float> device_eval_pdf(D3 n, D3 wo, double f0, double alpha, const std::vector<float>& wi) {
    const Device& d = device();
    const size_t m = wi.size() / 3;
    std::vector<float> wov;
    push3(wov, wo);
    cl::Buffer ob = d.input(wov), ib = d.input(wi), out = d.output(2 * m * sizeof(float));
    cl::Kernel k(d.program, "ggx_eval_pdf");
    k.setArg(0, float(n.x)), k.setArg(1, float(n.y)), k.setArg(2, float(n.z)), k.setArg(3, float(f0));
    k.setArg(4, float(alpha)), k.setArg(5, ob), k.setArg(6, ib), k.setArg(7, cl_uint(0)), k.setArg(8, out);
    d.run(k, m);
    return d.read<float>(out, 2 * m);
}

// Device ggx_sample: per sample (wi.xyz, weight, eval cos, pdf).
std::vector<float> device_samples(D3 n, D3 wo, double f0, double alpha, const std::vector<float>& u) {
    const Device& d = device();
    const size_t m = u.size() / 2;
    cl::Buffer ub = d.input(u), out = d.output(6 * m * sizeof(float));
    cl::Kernel k(d.program, "ggx_sample_many");
    k.setArg(0, float(n.x)), k.setArg(1, float(n.y)), k.setArg(2, float(n.z));
    k.setArg(3, float(wo.x)), k.setArg(4, float(wo.y)), k.setArg(5, float(wo.z));
    k.setArg(6, float(f0)), k.setArg(7, float(alpha)), k.setArg(8, ub), k.setArg(9, out);
    d.run(k, m);
    return d.read<float>(out, 6 * m);
}

std::vector<float> uniforms(size_t n, uint64_t seed) {
    std::mt19937_64 g(seed);
    std::vector<float> u(n);
    for (float& x : u) x = float(g() >> 40) * (1.0f / 16777216.0f);
    return u;
}

const D3 kNormal = normalized({0.3, -0.5, 0.8}); // tilted: ggx_sample's frame is exercised too

// wo at angle acos(cos_o) from kNormal, in the host frame; rounded to float as the device sees it.
D3 view(double cos_o) {
    D3 t, b;
    host_frame(kNormal, t, b);
    D3 w = normalized((std::sqrt(1 - cos_o * cos_o)) * t + cos_o * kNormal);
    return {float(w.x), float(w.y), float(w.z)};
}
D3 float_normal() { return {float(kNormal.x), float(kNormal.y), float(kNormal.z)}; }

const double kAlphas[] = {0.05, 0.2, 0.6, 1.0};
const double kViews[] = {1.0, 0.7, 0.2};

} // namespace

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

// ggx_eval and ggx_pdf against the double reference at random (wo, wi), including wi below the
// surface (both 0). Compared where both cosines exceed 1e-5: ggx_lambda clamps cos^2 at 1e-12 on
// purpose (no division by zero), which changes Lambda below cos 1e-6 (values there are checked
// for finiteness in GgxAtExtremesStaysFinite). Tolerance: relative 3e-3 of the value plus 1e-6
// of the lobe's peak. Float
// cancellation in D's t = cos_h^2 (alpha^2 - 1) + 1 near the peak costs 6e-8 / alpha^2 relative
// (2.4e-5 at alpha 0.05), and cos_h from a float half vector (1e-7 absolute) moves D by
// 4e-7 / alpha^2 relative there (1.6e-4): 3e-3 covers alpha >= 0.05 with margin.
TEST(Bsdf, GgxEvalAndPdfMatchReference) {
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
TEST(Bsdf, GgxEvalIsReciprocal) {
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
TEST(Bsdf, GgxPdfIntegratesToTheSampledFraction) {
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
TEST(Bsdf, GgxSampleMatchesPdfChiSquare) {
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
            std::vector<double> expected(nu * nphi + 1, 0), observed(nu * nphi + 1, 0);
            for (size_t i = 0; i < q.weight.size(); ++i) {
                int c = q.cell[i], bu = (c / (2 * nphi)) / 2, bp = (c % (2 * nphi)) / 2;
                expected[bu * nphi + bp] += m * v[2 * i + 1] * q.weight[i];
            }
            double inside = 0;
            for (int k = 0; k < nu * nphi; ++k) inside += expected[k];
            expected[nu * nphi] = std::max(0.0, m - inside);
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
TEST(Bsdf, GgxSampleWeightIsEvalCosOverPdf) {
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
TEST(Bsdf, GgxAlbedoIsAtMostOne) {
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
        hp.alpha = 0;
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

// At the extremes: alpha at material_alpha's floor (1e-4) and 1, views down to 1e-7 from grazing,
// u at 0 and 1 - 2^-24: wi finite and unit, weight finite in [0, 1] for F0 = 1 (the path tracer,
// photon tracer and eye pass sample every glossy surface this way); eval and pdf finite and
// non-negative for alpha >= 1e-3 (see GgxEvalAndPdfFiniteAtMaterialAlphaFloor for 1e-4).
TEST(Bsdf, GgxAtExtremesStaysFinite) {
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
TEST(Bsdf, GgxEvalAndPdfFiniteAtMaterialAlphaFloor) {
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
