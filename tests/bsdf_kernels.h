// The device side of the BSDF tests (bsdf_test.cpp, ggx_test.cpp): wrapper kernels around
// kernels/bsdf.cl, ggx.cl and hitpoint.cl, the harness that builds them once per test program,
// and the views and normals both tests use.
#pragma once
#include <cmath>
#include <random>
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

inline const D3 kNormal = normalized({0.3, -0.5, 0.8}); // tilted: ggx_sample's frame is exercised too

// wo at angle acos(cos_o) from kNormal, in the host frame; rounded to float as the device sees it.
inline D3 view(double cos_o) {
    D3 t, b;
    host_frame(kNormal, t, b);
    D3 w = normalized((std::sqrt(1 - cos_o * cos_o)) * t + cos_o * kNormal);
    return {float(w.x), float(w.y), float(w.z)};
}
inline D3 float_normal() { return {float(kNormal.x), float(kNormal.y), float(kNormal.z)}; }

inline const double kAlphas[] = {0.05, 0.2, 0.6, 1.0};
inline const double kViews[] = {1.0, 0.7, 0.2};

// Gauss-Legendre nodes on [0, 1] (4 points) for the quadratures of both tests.
inline const double kGlX[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
inline const double kGlW[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};

} // namespace clppm::test::bsdf
