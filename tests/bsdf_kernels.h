// The device side of the BSDF tests (bsdf_test.cpp, ggx_test.cpp): wrapper kernels around
// kernels/bsdf.cl, ggx.cl and hitpoint.cl, the harness that builds them once per test program,
// and the views and normals both tests use.
#pragma once
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "device/kernel_program.h"
#include "shared_types.h"
#include "test_util.h"

namespace clppm::test::bsdf {

inline const char* kWrappers = R"CL(
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
/* The whole model (kernels/bsdf.cl) from 15 parameters: base rgb, f0 rgb, f90, alpha, dielectric,
 * glass, metal, eta, thin, coat, coat alpha, sheen rgb, sheen roughness, iridescence weight,
 * film index, thickness, alpha_t (along make_frame's t), diffuse transmission dt and dt times its
 * colour; every normal is n. */
Bsdf test_bsdf(__global const float* p, float3 n) {
    Bsdf b;
    b.ns = n;
    b.ng = n;
    b.nl = n;
    b.base = (float3)(p[0], p[1], p[2]);
    b.f0 = (float3)(p[3], p[4], p[5]);
    b.f90 = p[6];
    b.alpha = p[7];
    b.dielectric = p[8];
    b.glass = p[9];
    b.metal = p[10];
    b.eta = p[11];
    b.thin = p[12] != 0.0f;
    b.radiance = false; /* the host references are written for importance, as the model is */
    b.front = true;
    b.sigma = (float3)(0.0f);
    b.nc = n;
    b.coat = p[13];
    b.coat_alpha = p[14];
    b.sheen = (float3)(p[15], p[16], p[17]);
    b.sheen_r = p[18];
    b.irid = p[19];
    b.irid_ior = p[20];
    b.irid_d = p[21];
    b.alpha_t = p[22];
    b.dt = p[23];
    b.translucent = (float3)(p[24], p[25], p[26]);
    float3 t, bt;
    make_frame(n, &t, &bt);
    b.ta = t;
    return b;
}
/* bsdf_eval (rgb) and bsdf_pdf at (wo, wi[i]) over the lobes in mask. Both wrappers are kept
 * unpacked on Intel's runtime, as the renderer's kernels are (kernels/portability.h): packed, its
 * code for bsdf_sample drew wrong, run-dependent samples (most rejected, pdfs off by 4x). */
__kernel SCALAR_WORK_ITEMS void model_eval_pdf(__global const float* p, float nx, float ny, float nz, float ox, float oy, float oz,
                             uint mask, __global const float* wi, __global float* out) {
    uint i = get_global_id(0);
    float3 n = (float3)(nx, ny, nz), wo = (float3)(ox, oy, oz);
    float3 w = (float3)(wi[3 * i], wi[3 * i + 1], wi[3 * i + 2]);
    Bsdf b = test_bsdf(p, n);
    float3 f = bsdf_eval(&b, wo, w, mask);
    out[4 * i] = f.x; out[4 * i + 1] = f.y; out[4 * i + 2] = f.z;
    out[4 * i + 3] = bsdf_pdf(&b, wo, w, mask);
}
/* bsdf_sample from wo with u[3 i .. 3 i + 2]: wi, weight, pdf, and flags (1 sampled, 2 delta,
 * 4 below), for a path carrying importance (radiance 0) or radiance. */
__kernel SCALAR_WORK_ITEMS void model_sample(__global const float* p, float nx, float ny, float nz, float ox, float oy, float oz,
                           uint mask, __global const float* u, uint radiance, __global float* out) {
    uint i = get_global_id(0);
    float3 n = (float3)(nx, ny, nz), wo = (float3)(ox, oy, oz);
    Bsdf b = test_bsdf(p, n);
    b.radiance = radiance != 0u;
    BsdfSample s;
    bool ok = bsdf_sample(&b, wo, mask, u[3 * i], u[3 * i + 1], u[3 * i + 2], &s);
    __global float* o = &out[8 * i];
    o[0] = s.wi.x; o[1] = s.wi.y; o[2] = s.wi.z;
    o[3] = s.weight.x; o[4] = s.weight.y; o[5] = s.weight.z;
    o[6] = s.pdf;
    o[7] = (float)((ok ? 1 : 0) | (s.delta ? 2 : 0) | (s.below ? 4 : 0));
}
/* irid_fresnel for (eta2, d, cos_1, f0 rgb) per item. */
__kernel void irid(__global const float* in, __global float* out) {
    uint i = get_global_id(0);
    __global const float* p = in + 6 * i;
    float3 r = irid_fresnel(p[0], p[1], p[2], (float3)(p[3], p[4], p[5]));
    out[3 * i] = r.x; out[3 * i + 1] = r.y; out[3 * i + 2] = r.z;
}
/* The diffuse lobe of a hit point's BSDF, seen from the normal. */
__kernel void lambert(__global const HitPoint* hp, float nx, float ny, float nz, __global const float* wi,
                      __global float* out) {
    uint i = get_global_id(0);
    float3 n = (float3)(nx, ny, nz);
    Bsdf b = hitpoint_bsdf(hp, n);
    b.nl = n; /* the hit point's stored normals are not set here: n is the surface */
    out[i] = bsdf_eval(&b, n, (float3)(wi[3 * i], wi[3 * i + 1], wi[3 * i + 2]), LOBE_DIFFUSE).y;
}
)CL";

struct Device : KernelHarness {
    // Include guards make the second file add only what the first lacked (hitpoint.cl).
    Device()
        : KernelHarness(assemble_kernel_source("portability.h") + assemble_kernel_source("bsdf.cl") +
                        assemble_kernel_source("hitpoint.cl") + kWrappers) {}

    // irid_fresnel per 6 floats (eta2, d, cos_1, f0 rgb): 3 floats each.
    std::vector<float> irid(const std::vector<float>& in) const {
        size_t n = in.size() / 6;
        cl::Buffer a = input(in), out = output(3 * n * sizeof(float));
        cl::Kernel k(program, "irid");
        k.setArg(0, a), k.setArg(1, out);
        run(k, n);
        return read<float>(out, 3 * n);
    }

    std::vector<float> fresnel(const std::vector<float>& cos_eta) const {
        size_t n = cos_eta.size() / 2;
        cl::Buffer in = input(cos_eta), out = output(n * sizeof(float));
        cl::Kernel k(program, "fresnel");
        k.setArg(0, in), k.setArg(1, out);
        run(k, n);
        return read<float>(out, n);
    }
};

inline const Device& device() {
    static Device d;
    return d;
}

inline void push3(std::vector<float>& v, D3 a) {
    v.push_back(float(a.x)), v.push_back(float(a.y)), v.push_back(float(a.z));
}
inline D3 at3(const std::vector<float>& v, size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }

// Device ggx_eval and ggx_pdf at (wo, wi[k]): values interleaved (eval, pdf).
inline std::vector<float> device_eval_pdf(D3 n, D3 wo, double f0, double alpha, const std::vector<float>& wi) {
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
inline std::vector<float> device_samples(D3 n, D3 wo, double f0, double alpha, const std::vector<float>& u) {
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

inline std::vector<float> uniforms(size_t n, uint64_t seed) {
    std::mt19937_64 g(seed);
    std::vector<float> u(n);
    for (float& x : u) x = float(g() >> 40) * (1.0f / 16777216.0f);
    return u;
}

// ---- the whole model (kernels/bsdf.cl) through the wrappers above ----

constexpr unsigned kDiffuse = 1, kSpecular = 2, kGlass = 4, kMetal = 8, kCoat = 16, kSheen = 32, kAll = 63;

struct Params {
    D3 base{1, 1, 1}, f0{0.04, 0.04, 0.04};
    double f90 = 1, alpha = 0.25, dielectric = 1, glass = 0, metal = 0, eta = 1.5;
    bool thin = false;
    double coat = 0, coat_alpha = 0;               // KHR_materials_clearcoat, on the same normal
    D3 sheen{0, 0, 0};                             // KHR_materials_sheen's colour
    double sheen_r = 1;                            // and roughness (at least SHEEN_MIN_ROUGHNESS)
    double irid = 0, irid_ior = 1.3, irid_d = 400; // KHR_materials_iridescence
    double alpha_t = -1;                           // KHR_materials_anisotropy: alpha along t (-1: alpha)
    double dt = 0;                                 // KHR_materials_diffuse_transmission's weight
    D3 dt_color{1, 1, 1};                          // and colour
    std::vector<float> pack() const {
        return {float(base.x),
                float(base.y),
                float(base.z),
                float(f0.x),
                float(f0.y),
                float(f0.z),
                float(f90),
                float(alpha),
                float(dielectric),
                float(glass),
                float(metal),
                float(eta),
                thin ? 1.f : 0.f,
                float(coat),
                float(coat_alpha),
                float(sheen.x),
                float(sheen.y),
                float(sheen.z),
                float(sheen_r),
                float(irid),
                float(irid_ior),
                float(irid_d),
                float(alpha_t < 0 ? alpha : alpha_t),
                float(dt),
                float(dt * dt_color.x),
                float(dt * dt_color.y),
                float(dt * dt_color.z)};
    }
    std::string name() const {
        return "base (" + std::to_string(base.x) + "," + std::to_string(base.y) + "," + std::to_string(base.z) +
               ") alpha " + std::to_string(alpha) + " dielectric " + std::to_string(dielectric) + " metal " +
               std::to_string(metal) + " glass " + std::to_string(glass) + " eta " + std::to_string(eta) +
               (thin ? " thin" : "") + " f90 " + std::to_string(f90) +
               (coat > 0 ? " coat " + std::to_string(coat) + " alpha " + std::to_string(coat_alpha) : "") +
               (sheen.x + sheen.y + sheen.z > 0 ? " sheen " + std::to_string(sheen.x) + " r " + std::to_string(sheen_r)
                                                : "") +
               (irid > 0 ? " iridescence " + std::to_string(irid) + " d " + std::to_string(irid_d) : "") +
               (alpha_t >= 0 ? " alpha_t " + std::to_string(alpha_t) : "") +
               (dt > 0 ? " diffuse transmission " + std::to_string(dt) : "");
    }
};

// Per wi: f.rgb and pdf.
inline std::vector<float> model_eval(const Params& p, D3 n, D3 wo, const std::vector<float>& wi, unsigned mask) {
    const Device& d = device();
    const size_t m = wi.size() / 3;
    cl::Buffer pb = d.input(p.pack()), ib = d.input(wi), out = d.output(4 * m * sizeof(float));
    cl::Kernel k(d.program, "model_eval_pdf");
    k.setArg(0, pb), k.setArg(1, float(n.x)), k.setArg(2, float(n.y)), k.setArg(3, float(n.z));
    k.setArg(4, float(wo.x)), k.setArg(5, float(wo.y)), k.setArg(6, float(wo.z)), k.setArg(7, cl_uint(mask));
    k.setArg(8, ib), k.setArg(9, out);
    d.run(k, m);
    return d.read<float>(out, 4 * m);
}

// Per sample: wi, weight, pdf, flags (1 sampled, 2 delta, 4 below).
inline std::vector<float> model_sample(const Params& p, D3 n, D3 wo, size_t m, unsigned mask, uint64_t seed,
                                       bool radiance = false) {
    const Device& d = device();
    cl::Buffer pb = d.input(p.pack()), ub = d.input(uniforms(3 * m, seed)), out = d.output(8 * m * sizeof(float));
    cl::Kernel k(d.program, "model_sample");
    k.setArg(0, pb), k.setArg(1, float(n.x)), k.setArg(2, float(n.y)), k.setArg(3, float(n.z));
    k.setArg(4, float(wo.x)), k.setArg(5, float(wo.y)), k.setArg(6, float(wo.z)), k.setArg(7, cl_uint(mask));
    k.setArg(8, ub), k.setArg(9, cl_uint(radiance)), k.setArg(10, out);
    d.run(k, m);
    return d.read<float>(out, 8 * m);
}

// Random unit directions, a quarter of them below the surface.
inline std::vector<float> random_directions(D3 n, size_t m, uint64_t seed) {
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<float> v;
    while (v.size() < 3 * m) {
        D3 w{u(g), u(g), u(g)};
        double l = length(w);
        if (l < 0.1 || l > 1) continue;
        w = (1 / l) * w;
        if (dot(w, n) < 0 && (v.size() / 3) % 4 != 0) w = w - (2 * dot(w, n)) * n;
        push3(v, w);
    }
    return v;
}

inline const D3 kNormal = normalized({0.3, -0.5, 0.8}); // tilted: ggx_sample's frame is exercised too

// wo at angle acos(cos_o) from kNormal, in the host frame; rounded to float as the device sees it.
inline D3 view(double cos_o) {
    D3 t, b;
    host_frame(kNormal, t, b);
    D3 w = normalized((std::sqrt(1 - cos_o * cos_o)) * t + cos_o * kNormal);
    return {float(w.x), float(w.y), float(w.z)};
}
// kernels/sampling.cl make_frame's t (Duff et al. 2017), the test BSDF's anisotropy direction.
inline D3 kernel_tangent(D3 n) {
    const D3 f{float(n.x), float(n.y), float(n.z)};
    const double sign = f.z >= 0 ? 1 : -1, a = -1 / (sign + f.z), c = f.x * f.y * a;
    return {1 + sign * f.x * f.x * a, sign * c, -sign * f.x};
}

inline D3 float_normal() { return {float(kNormal.x), float(kNormal.y), float(kNormal.z)}; }

inline const double kAlphas[] = {0.05, 0.2, 0.6, 1.0};
inline const double kViews[] = {1.0, 0.7, 0.2};

// Gauss-Legendre nodes on [0, 1] (4 points) for the quadratures of both tests.
inline const double kGlX[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
inline const double kGlW[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};

// ---- host references and quadrature shared by the BSDF tests ----

// GGX (Walter et al. 2007, Eq. 33), Smith Lambda (Heitz 2014, Eq. 72), height-correlated G2
// (Heitz 2014, Eq. 99), Schlick's Fresnel.
inline double ref_d(double c, double a) {
    double t = c * c * (a * a - 1) + 1;
    return a * a / (M_PI * t * t);
}
inline double ref_lambda(double c, double a) { return 0.5 * (-1 + std::sqrt(1 + a * a * (1 - c * c) / (c * c))); }
// KHR_materials_sheen's "Sheen visibility": Estevez and Kulla's (2017) fit of the Charlie
// microfibres' Lambda, as the extension writes it (l, lambdaSheen).
inline double ref_sheen_lambda(double cos_t, double alpha) {
    auto l = [alpha](double x) {
        const double t = (1 - alpha) * (1 - alpha);
        auto mix = [t](double a, double b) { return a * (1 - t) + b * t; };
        return mix(21.5473, 25.3245) / (1 + mix(3.82987, 3.32435) * std::pow(std::max(x, 0.0), mix(0.19823, 0.16801))) +
               mix(-1.97760, -1.27393) * x + mix(-4.32054, -4.85967);
    };
    return std::fabs(cos_t) < 0.5 ? std::exp(l(cos_t)) : std::exp(2 * l(0.5) - l(1 - cos_t));
}
// KHR_materials_sheen's lobe as the extension writes it, alphaG the roughness squared (as the
// Khronos sample viewer takes it): its "Sheen distribution" and "Sheen visibility".
inline double ref_sheen_d(double sheen_roughness, double n_dot_h) {
    const double alpha_g = sheen_roughness * sheen_roughness, inv_r = 1 / alpha_g;
    const double sin2h = std::max(0.0, 1 - n_dot_h * n_dot_h); // rounding can put n.h above 1
    return (2 + inv_r) * std::pow(sin2h, inv_r * 0.5) / (2 * M_PI);
}
inline double ref_sheen_v(double n_dot_l, double n_dot_v, double sheen_roughness) {
    const double alpha_g = sheen_roughness * sheen_roughness;
    return 1 /
           ((1 + ref_sheen_lambda(n_dot_v, alpha_g) + ref_sheen_lambda(n_dot_l, alpha_g)) * (4 * n_dot_v * n_dot_l));
}
// The lobe's directional albedo E(mu) = int D V cos_l dl, by the midpoint rule over (theta_l, phi)
// in n x n cells (independent of scripts/make_sheen_albedo.cpp's Gauss-Legendre panels).
inline double ref_sheen_albedo(double mu, double sheen_roughness, int n) {
    const double so = std::sqrt(1 - mu * mu);
    double e = 0;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y) {
            const double th = (x + 0.5) / n * M_PI / 2, phi = (y + 0.5) / n * 2 * M_PI;
            const double cl = std::cos(th), sl = std::sin(th);
            const D3 h = normalized(D3{sl * std::cos(phi) + so, sl * std::sin(phi), cl + mu});
            e += ref_sheen_d(sheen_roughness, h.z) * ref_sheen_v(cl, mu, sheen_roughness) * cl * sl * (M_PI / 2 / n) *
                 (2 * M_PI / n);
        }
    return e;
}
inline double ref_eval(D3 n, D3 wo, D3 wi, double f0, double a) {
    double co = dot(n, wo), ci = dot(n, wi);
    if (co <= 0 || ci <= 0) return 0;
    D3 h = normalized(wo + wi);
    double F = f0 + (1 - f0) * std::pow(1 - dot(wi, h), 5);
    return F * ref_d(dot(n, h), a) / (1 + ref_lambda(co, a) + ref_lambda(ci, a)) / (4 * co * ci);
}
inline double ref_pdf(D3 n, D3 wo, D3 wi, double a) {
    double co = dot(n, wo), ci = dot(n, wi);
    if (co <= 0 || ci <= 0) return 0;
    D3 h = normalized(wo + wi);
    return ref_d(dot(n, h), a) / (1 + ref_lambda(co, a)) / (4 * co);
}

// Fresnel for unpolarised light from the Fresnel equations in Hecht's form (Optics, Eq. 4.42-4.43):
// Rs = sin^2(ti - tt) / sin^2(ti + tt), Rp = tan^2(ti - tt) / tan^2(ti + tt); 1 under TIR.
inline double ref_fresnel_hecht(double cos_i, double eta) {
    if (cos_i >= 1) return std::pow((eta - 1) / (eta + 1), 2);
    double ti = std::acos(cos_i), s = std::sin(ti) / eta;
    if (s >= 1) return 1;
    double tt = std::asin(s);
    double rs = std::sin(ti - tt) / std::sin(ti + tt), rp = std::tan(ti - tt) / std::tan(ti + tt);
    return 0.5 * (rs * rs + rp * rp);
}

// The rough dielectric of Walter et al. 2007 as the renderer defines it (kernels/bsdf.cl's
// header): wo above n, eta the relative index of wi's side below. Reflection F D G2 / (4 cos_o
// cos_i) (Eq. 20); transmission through the generalised half vector h_t = -(wo + eta wi) (Eq. 16)
// with (1 - F) D G2 |wo.h| |wi.h| eta^2 / (|cos_o cos_i| (wo.h + eta wi.h)^2) (Eq. 21, with eta^2
// of the side of wi: flux form); thin-walled, the reflection lobe mirrored below. `tint` scales
// the transmission. Written from the paper, not from the kernel.
inline double ref_rough_glass(D3 n, D3 wo, D3 wi, double alpha, double eta, bool thin, double tint) {
    const double co = dot(n, wo), ci = dot(n, wi);
    if (co <= 0 || ci == 0) return 0;
    const auto g2 = [&](double a, double b) { return 1 / (1 + ref_lambda(a, alpha) + ref_lambda(b, alpha)); };
    if (ci > 0 || thin) {
        const D3 wr = ci > 0 ? wi : wi - (2 * ci) * n;
        const D3 h = normalized(wo + wr);
        const double F = ref_fresnel_hecht(dot(wo, h), eta);
        const double r = ref_d(dot(n, h), alpha) * g2(co, std::fabs(ci)) / (4 * co * std::fabs(ci));
        return ci > 0 ? F * r : tint * (1 - F) * r;
    }
    D3 h = normalized(-1.0 * (wo + eta * wi));
    if (dot(h, n) < 0) h = -1.0 * h;
    const double oh = dot(wo, h), ih = dot(wi, h);
    if (oh <= 0 || ih >= 0) return 0;
    const double F = ref_fresnel_hecht(oh, eta);
    return tint * (1 - F) * ref_d(dot(n, h), alpha) * g2(co, -ci) * oh * -ih * eta * eta /
           (co * -ci * std::pow(oh + eta * ih, 2));
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
    // The cell of wi_ in a grid of nu x nphi equal cells over (u, phi), row by row.
    int cell(D3 wi_, int nu, int nphi) const {
        double u, phi;
        coords(wi_, &u, &phi);
        return std::min(nu - 1, int(u * nu)) * nphi + std::min(nphi - 1, int(phi / (2 * M_PI) * nphi));
    }
};

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
inline void quadrature_cell(const HalfVectorGrid& g, double u0, double u1, double p0, double p1, int depth, int id,
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
            if (dot(g.wo, h) <= 0 || dot(g.wi(h), g.n) <= 0) continue; // below: not reflection's to count
            push3(q.wi, normalized(g.wi(h)));
            q.weight.push_back(kGlW[a] * kGlW[c] * du * dp * g.jacobian(h));
            q.cell.push_back(id);
        }
}
inline Quadrature half_vector_quadrature(const HalfVectorGrid& g, int nu, int nphi, int depth = 6) {
    Quadrature q;
    const double du = 1.0 / nu, dp = 2 * M_PI / nphi;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nphi; ++j)
            quadrature_cell(g, i * du, (i + 1) * du, j * dp, (j + 1) * dp, depth, i * nphi + j, q);
    return q;
}

// The expected counts of m samples in the nu x nphi bins of a chi-square test: each quadrature
// cell of q (sub x sub of them per bin) adds m pdf weight to its bin, pdf[stride i + offset] the
// density at q.wi[i]; the extra last bin expects what the bins leave of m.
inline std::vector<double> expected_bin_counts(const Quadrature& q, const std::vector<float>& pdf, size_t stride,
                                               size_t offset, int nu, int nphi, int sub, size_t m) {
    std::vector<double> expected(size_t(nu * nphi) + 1, 0);
    for (size_t i = 0; i < q.weight.size(); ++i) {
        const int c = q.cell[i], bu = (c / (sub * nphi)) / sub, bp = (c % (sub * nphi)) / sub;
        expected[size_t(bu * nphi + bp)] += double(m) * pdf[stride * i + offset] * q.weight[i];
    }
    double inside = 0;
    for (int k = 0; k < nu * nphi; ++k) inside += expected[size_t(k)];
    expected[size_t(nu * nphi)] = std::max(0.0, double(m) - inside);
    return expected;
}

} // namespace clppm::test::bsdf
