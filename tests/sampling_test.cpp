// kernels/sampling.cl on the device against host references: chi-square tests of the cosine,
// cone and triangle samplers against their pdfs integrated per bin (bins in (cos theta, phi), as
// pbrt-v4's and Mitsuba's warp tests), the octahedral normal encoding's round-trip error over
// all directions including the poles, the equator and the octahedron's folds, and the
// orthonormality of make_frame, including the -z pole where naive constructions break.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "device/kernel_program.h"
#include "stat_tests.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

const char* kWrappers = R"CL(
__kernel void cosine_dirs(float nx, float ny, float nz, __global const float* u, __global float* out) {
    uint i = get_global_id(0);
    float3 d = sample_cosine_hemisphere((float3)(nx, ny, nz), u[2 * i], u[2 * i + 1]);
    out[3 * i] = d.x; out[3 * i + 1] = d.y; out[3 * i + 2] = d.z;
}
__kernel void cone_dirs(float ax, float ay, float az, float cos_max, __global const float* u, __global float* out) {
    uint i = get_global_id(0);
    float3 d = sample_cone((float3)(ax, ay, az), cos_max, u[2 * i], u[2 * i + 1]);
    out[3 * i] = d.x; out[3 * i + 1] = d.y; out[3 * i + 2] = d.z;
}
__kernel void triangle_bary(__global const float* u, __global float* out) {
    uint i = get_global_id(0);
    float2 b = sample_triangle(u[2 * i], u[2 * i + 1]);
    out[2 * i] = b.x; out[2 * i + 1] = b.y;
}
__kernel void oct_roundtrip(__global const float* dirs, __global uint* codes, __global float* out) {
    uint i = get_global_id(0);
    uint e = oct_encode((float3)(dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]));
    codes[i] = e;
    float3 d = oct_decode(e);
    out[3 * i] = d.x; out[3 * i + 1] = d.y; out[3 * i + 2] = d.z;
}
__kernel void oct_decode_codes(__global const uint* codes, __global float* out) {
    uint i = get_global_id(0);
    float3 d = oct_decode(codes[i]);
    out[3 * i] = d.x; out[3 * i + 1] = d.y; out[3 * i + 2] = d.z;
}
__kernel void frames(__global const float* n, __global float* out) {
    uint i = get_global_id(0);
    float3 t, b;
    make_frame((float3)(n[3 * i], n[3 * i + 1], n[3 * i + 2]), &t, &b);
    out[6 * i] = t.x; out[6 * i + 1] = t.y; out[6 * i + 2] = t.z;
    out[6 * i + 3] = b.x; out[6 * i + 4] = b.y; out[6 * i + 5] = b.z;
}
)CL";

struct Device : KernelHarness {
    Device() : KernelHarness(assemble_kernel_source("sampling.cl") + kWrappers) {}
};

const Device& device() {
    static Device d;
    return d;
}

// Uniforms as the renderer draws them: 24-bit multiples of 2^-24 in [0, 1), from an independent
// host generator.
std::vector<float> uniforms(size_t n, uint64_t seed) {
    std::mt19937_64 g(seed);
    std::vector<float> u(n);
    for (float& x : u) x = float(g() >> 40) * (1.0f / 16777216.0f);
    return u;
}

// Histogram of device directions in (cos theta, phi) about axis n; `outside` counts directions
// whose cos theta is outside the binned range. Float directions carry ~1e-7 of rounding, so a
// cos theta within 1e-6 above 1 or below `rim` (a cone's cos_max; the leak itself is asserted
// separately with that tolerance) is counted at the edge it rounded across.
std::vector<double> histogram(const std::vector<float>& dirs, D3 n, const SphereBins& bins, size_t* outside,
                              double rim = -2) {
    D3 t, b;
    host_frame(n, t, b);
    std::vector<double> h(bins.size(), 0);
    *outside = 0;
    for (size_t i = 0; i < dirs.size() / 3; ++i) {
        D3 d{dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]};
        double c = dot(d, n);
        if (c > 1 && c < 1 + 1e-6) c = 1;
        if (c < rim + 1e-9 && c > rim - 1e-6) c = rim + 1e-9; // + 1e-9: clear of the bin edge's rounding
        int k = bins.index(c, std::atan2(dot(d, b), dot(d, t)));
        if (k < 0) ++*outside;
        else h[k] += 1;
    }
    return h;
}

const std::vector<D3> kAxes = {{0, 0, 1},
                               {0, 0, -1},
                               {1, 0, 0},
                               {0, -1, 0},
                               normalized({0.3, -0.5, 0.8}),
                               normalized({1e-4, 2e-4, -1}),
                               normalized({-0.7, 0.7, -0.1})};

std::string describe(D3 n) {
    return "(" + std::to_string(n.x) + ", " + std::to_string(n.y) + ", " + std::to_string(n.z) + ")";
}

// Significance per chi-square test: 1e-3 spread over the (at most 40) tests of this program.
const double kAlpha = sidak(1e-3, 40);

// Directions for a kernel's input, x, y, z floats each: given ones made unit, exact values (signed
// zeros) kept as they are, and Gaussian ones (uniform over the sphere once made unit).
struct DirectionList {
    std::vector<float> xyz;
    void unit(D3 v) {
        v = normalized(v);
        xyz.insert(xyz.end(), {float(v.x), float(v.y), float(v.z)});
    }
    void exact(const std::array<float, 3>& v) { xyz.insert(xyz.end(), v.begin(), v.end()); }
    void gaussian(std::mt19937_64& g, int count) {
        std::normal_distribution<double> gauss;
        for (int i = 0; i < count; ++i) unit({gauss(g), gauss(g), gauss(g)});
    }
    size_t size() const { return xyz.size() / 3; }
};

} // namespace

// pdf = cos(theta) / pi on the hemisphere about n, zero below: 1M samples per axis in 20 x 16
// bins over the whole sphere, so that any sample below the surface fails the test outright.
TEST(Sampling, CosineHemisphereMatchesPdfChiSquare) {
    const Device& d = device();
    const size_t n = 1000000;
    std::vector<float> u = uniforms(2 * n, 11);
    cl::Buffer ub = d.input(u), ob(d.dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
    SphereBins bins{20, 16, -1, 1};
    auto pdf = [](double c, double) { return c > 0 ? c / M_PI : 0.0; };
    std::vector<double> expected = bins.expected(pdf, n);
    double total = 0;
    for (double e : expected) total += e;
    EXPECT_NEAR(total / n, 1.0, 1e-9) << "the reference pdf integrates to 1 over the sphere";
    for (D3 axis : kAxes) {
        cl::Kernel k(d.program, "cosine_dirs");
        k.setArg(0, float(axis.x)), k.setArg(1, float(axis.y)), k.setArg(2, float(axis.z)), k.setArg(3, ub),
            k.setArg(4, ob);
        d.run(k, n);
        std::vector<float> dirs = d.read<float>(ob, 3 * n);
        double min_cos = 1, max_len_err = 0;
        for (size_t i = 0; i < n; ++i) {
            D3 v{dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]};
            min_cos = std::min(min_cos, dot(v, axis));
            max_len_err = std::max(max_len_err, std::fabs(std::sqrt(dot(v, v)) - 1));
        }
        // Float normalisation: a few ulps. The axis itself is rounded to float (1e-7).
        EXPECT_LT(max_len_err, 1e-6) << describe(axis);
        EXPECT_GT(min_cos, -1e-6) << describe(axis) << ": a sample below the surface";
        size_t outside = 0;
        Chi2Result c = chi2_test(histogram(dirs, axis, bins, &outside), expected);
        EXPECT_TRUE(c.error.empty()) << describe(axis) << ": " << c.error;
        EXPECT_GT(c.p_value, kAlpha) << describe(axis) << ": chi2 " << c.chi2 << " dof " << c.dof;
    }
}

// Uniform in the cone: pdf = 1 / (2 pi (1 - cos_max)) for cos theta >= cos_max. Bin edges sit on
// cos_max with two empty bins below it, so any leak out of the cone fails the test.
TEST(Sampling, ConeMatchesPdfChiSquare) {
    const Device& d = device();
    const size_t n = 500000;
    std::vector<float> u = uniforms(2 * n, 12);
    cl::Buffer ub = d.input(u), ob(d.dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
    for (double cos_max : {0.999, 0.95, 0.5, 0.0, -0.7, -1.0})
        for (D3 axis : {kAxes[0], kAxes[1], kAxes[4], kAxes[5]}) {
            const float cm = float(cos_max);
            const int inside = 12;
            const double w = (1 - double(cm)) / inside;
            SphereBins bins{inside, 12, double(cm), 1};
            if (double(cm) - 2 * w >= -1) bins = SphereBins{inside + 2, 12, double(cm) - 2 * w, 1};
            auto pdf = [cm](double c, double) { return c >= double(cm) ? 1.0 / (2 * M_PI * (1 - double(cm))) : 0.0; };
            cl::Kernel k(d.program, "cone_dirs");
            k.setArg(0, float(axis.x)), k.setArg(1, float(axis.y)), k.setArg(2, float(axis.z)), k.setArg(3, cm);
            k.setArg(4, ub), k.setArg(5, ob);
            d.run(k, n);
            std::vector<float> dirs = d.read<float>(ob, 3 * n);
            double min_cos = 1;
            for (size_t i = 0; i < n; ++i)
                min_cos = std::min(min_cos, dot({dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]}, axis));
            // 1e-6: float rounding of the direction and of the float axis.
            EXPECT_GE(min_cos, double(cm) - 1e-6) << "cos_max " << cos_max << " axis " << describe(axis);
            size_t outside = 0;
            std::vector<double> h = histogram(dirs, axis, bins, &outside, double(cm));
            EXPECT_EQ(outside, 0u) << "cos_max " << cos_max;
            std::vector<double> expected = bins.expected(pdf, n);
            double total = 0;
            for (double e : expected) total += e;
            EXPECT_NEAR(total / n, 1.0, 1e-9) << "cos_max " << cos_max << ": the reference pdf integrates to 1";
            Chi2Result c = chi2_test(h, expected);
            EXPECT_TRUE(c.error.empty()) << "cos_max " << cos_max << " axis " << describe(axis) << ": " << c.error;
            EXPECT_GT(c.p_value, kAlpha) << "cos_max " << cos_max << " axis " << describe(axis) << ": chi2 " << c.chi2
                                         << " dof " << c.dof;
        }
}

namespace {

// Every direction of v (x, y, z floats, drawn from the pairs u) finite, unit to 1e-6 and within
// cos_max of axis.
void expect_unit_within(const std::vector<float>& v, const std::vector<float>& u, D3 axis, float cos_max) {
    for (size_t i = 0; i < v.size() / 3; ++i) {
        D3 dir{v[3 * i], v[3 * i + 1], v[3 * i + 2]};
        ASSERT_TRUE(std::isfinite(dir.x) && std::isfinite(dir.y) && std::isfinite(dir.z));
        EXPECT_NEAR(std::sqrt(dot(dir, dir)), 1.0, 1e-6);
        EXPECT_GE(dot(dir, axis), double(cos_max) - 1e-6)
            << "cos_max " << cos_max << " u " << u[2 * i] << "," << u[2 * i + 1];
    }
}

} // namespace

// A cone narrower than float resolution around 1 and the u extremes still give unit directions
// inside the cone.
TEST(Sampling, ConeAndHemisphereAtExtremeInputsAreFiniteUnitAndInside) {
    const Device& d = device();
    const float top = 1.0f - 1.0f / 16777216.0f;
    std::vector<float> u;
    for (float a : {0.0f, 1e-7f, 0.5f, top})
        for (float b : {0.0f, 0.25f, top}) u.push_back(a), u.push_back(b);
    const size_t n = u.size() / 2;
    cl::Buffer ub = d.input(u), ob(d.dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
    for (D3 axis : kAxes) {
        for (float cm : {1.0f, 0.9999999f, -1.0f}) {
            cl::Kernel k(d.program, "cone_dirs");
            k.setArg(0, float(axis.x)), k.setArg(1, float(axis.y)), k.setArg(2, float(axis.z)), k.setArg(3, cm);
            k.setArg(4, ub), k.setArg(5, ob);
            d.run(k, n);
            expect_unit_within(d.read<float>(ob, 3 * n), u, axis, cm);
        }
        cl::Kernel k(d.program, "cosine_dirs");
        k.setArg(0, float(axis.x)), k.setArg(1, float(axis.y)), k.setArg(2, float(axis.z)), k.setArg(3, ub),
            k.setArg(4, ob);
        d.run(k, n);
        std::vector<float> v = d.read<float>(ob, 3 * n);
        expect_unit_within(v, u, axis, 0.0f);
        // u1 = 0 is the normal itself.
        D3 first{v[0], v[1], v[2]};
        EXPECT_NEAR(dot(first, axis), 1.0, 1e-6);
    }
}

// Uniform over the triangle: barycentrics (b1, b2) fill {b1, b2 >= 0, b1 + b2 <= 1} with density 2.
// 32 x 32 square cells: inside cells expect 2 h^2, diagonal cells h^2 (half inside), the rest 0.
TEST(Sampling, TriangleIsUniformByAreaChiSquare) {
    const Device& d = device();
    const size_t n = 1000000;
    std::vector<float> u = uniforms(2 * n, 13);
    cl::Buffer ub = d.input(u), ob(d.dc.context, CL_MEM_WRITE_ONLY, 2 * n * sizeof(float));
    cl::Kernel k(d.program, "triangle_bary");
    k.setArg(0, ub), k.setArg(1, ob);
    d.run(k, n);
    std::vector<float> b = d.read<float>(ob, 2 * n);
    const int g = 32;
    const double h = 1.0 / g;
    std::vector<double> observed(g * g, 0), expected(g * g, 0);
    for (int i = 0; i < g; ++i)
        for (int j = 0; j < g; ++j)
            expected[i * g + j] = n * 2 * (i + j < g - 1 ? h * h : i + j == g - 1 ? h * h / 2 : 0);
    for (size_t s = 0; s < n; ++s) {
        double b1 = b[2 * s], b2 = b[2 * s + 1];
        // 1e-7: 1 - sqrt(u) rounds up by at most half an ulp of 1.
        ASSERT_TRUE(b1 >= 0 && b2 >= 0 && b1 + b2 <= 1 + 1e-7) << b1 << ", " << b2;
        int i = std::min(g - 1, int(b1 * g)), j = std::min(g - 1, int(b2 * g));
        observed[i * g + j] += 1;
    }
    Chi2Result c = chi2_test(observed, expected);
    EXPECT_TRUE(c.error.empty()) << c.error;
    EXPECT_GT(c.p_value, kAlpha) << "chi2 " << c.chi2 << " dof " << c.dof;
    // The corners: u1 = 0 is vertex 2; u1 -> 1 with u2 = 0 is vertex 0, with u2 -> 1 vertex 1.
    const float top = 1.0f - 1.0f / 16777216.0f;
    std::vector<float> corners = {0.0f, 0.3f, top, 0.0f, top, top};
    cl::Buffer cb = d.input(corners), cob(d.dc.context, CL_MEM_WRITE_ONLY, 6 * sizeof(float));
    k.setArg(0, cb), k.setArg(1, cob);
    d.run(k, 3);
    std::vector<float> cv = d.read<float>(cob, 6);
    const double want[6] = {0, 1, 0, 0, 1, 0};
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(cv[i], want[i], 3e-7) << "corner value " << i; // a few ulps of 1
}

// oct_decode(oct_encode(n)) over 1M uniform directions and the special ones (poles, +-axes, the
// equator, octant diagonals, the folds of the lower hemisphere, signed zeros, tiny components).
// Bound: 16 bits per coordinate over [-1, 1] leave |dp| <= sqrt(2) / 65535 = 2.2e-5 in the
// octahedral plane; lifting to the octahedron stretches by at most sqrt(3) and normalising by at
// most sqrt(3), so the angle error stays below 3 * 2.2e-5 = 6.5e-5 rad; 7e-5 leaves room for float.
TEST(Sampling, OctahedralRoundTripErrorIsBounded) {
    const Device& d = device();
    DirectionList dirs;
    for (double s : {1.0, -1.0}) {
        dirs.unit({s, 0, 0}), dirs.unit({0, s, 0}), dirs.unit({0, 0, s});
        for (double e : {1e-3, 1e-5, 1e-7, 1e-20})
            dirs.unit({e, -e, s}), dirs.unit({s, e, e}), dirs.unit({e, s, -e}), dirs.unit({1, s, e}),
                dirs.unit({1, s, -e});
        for (double a : {1.0, -1.0})
            for (double b : {1.0, -1.0})
                dirs.unit({a, b, s}), dirs.unit({a, b, 0}), dirs.unit({a * 0.25, b * 0.75, s * 1e-4});
    }
    // Signed zeros (normalized() would keep them, push them directly).
    for (std::array<float, 3> v :
         {std::array<float, 3>{-0.0f, -0.0f, -1.0f}, {-0.0f, 0.0f, 1.0f}, {1.0f, -0.0f, -0.0f}, {-0.0f, -1.0f, -0.0f}})
        dirs.exact(v);
    const size_t special = dirs.size();
    std::mt19937_64 g(14);
    dirs.gaussian(g, 1000000);
    const size_t n = dirs.size();
    cl::Buffer db = d.input(dirs.xyz), cb(d.dc.context, CL_MEM_WRITE_ONLY, n * sizeof(cl_uint)),
               ob(d.dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
    cl::Kernel k(d.program, "oct_roundtrip");
    k.setArg(0, db), k.setArg(1, cb), k.setArg(2, ob);
    d.run(k, n);
    std::vector<float> out = d.read<float>(ob, 3 * n);
    double worst = 0, worst_special = 0, worst_len = 0;
    size_t worst_i = 0, flipped = 0;
    for (size_t i = 0; i < n; ++i) {
        D3 a{dirs.xyz[3 * i], dirs.xyz[3 * i + 1], dirs.xyz[3 * i + 2]}, b{out[3 * i], out[3 * i + 1], out[3 * i + 2]};
        ASSERT_TRUE(std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.z)) << "direction " << i;
        double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b));
        worst_len = std::max(worst_len, std::fabs(lb - 1));
        double angle = std::atan2(std::sqrt(dot(cross(a, b), cross(a, b))), dot(a, b) / la);
        if (angle > worst) worst = angle, worst_i = i;
        if (i < special) worst_special = std::max(worst_special, angle);
        // A normal must stay on its side of the surface: z keeps its sign whenever |z| exceeds
        // the error bound.
        if (std::fabs(a.z) > 7e-5 && (a.z > 0) != (b.z > 0)) ++flipped;
    }
    EXPECT_LT(worst, 7e-5) << "direction " << worst_i << " "
                           << describe({dirs.xyz[3 * worst_i], dirs.xyz[3 * worst_i + 1], dirs.xyz[3 * worst_i + 2]});
    EXPECT_LT(worst_special, 7e-5);
    EXPECT_LT(worst_len, 1e-6);
    EXPECT_EQ(flipped, 0u);
    std::printf("oct round trip: max angle error %.3g rad (special directions %.3g)\n", worst, worst_special);
}

// Every one of a spread of codes (all four edges of the 16-bit square, its centre, random ones)
// decodes to a finite unit vector, and re-encoding a decoded vector moves it by at most one step.
TEST(Sampling, OctahedralDecodeOfAnyCodeIsUnitAndStable) {
    const Device& d = device();
    std::vector<cl_uint> codes;
    for (uint32_t a = 0; a < 65536; a += 257)
        for (uint32_t b : {0u, 1u, 32767u, 32768u, 65534u, 65535u})
            codes.push_back(a | (b << 16)), codes.push_back(b | (a << 16));
    std::mt19937 g(15);
    for (int i = 0; i < 200000; ++i) codes.push_back(g());
    const size_t n = codes.size();
    cl::Buffer cb = d.input(codes), ob(d.dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
    cl::Kernel k(d.program, "oct_decode_codes");
    k.setArg(0, cb), k.setArg(1, ob);
    d.run(k, n);
    std::vector<float> dec = d.read<float>(ob, 3 * n);
    for (size_t i = 0; i < n; ++i) {
        D3 v{dec[3 * i], dec[3 * i + 1], dec[3 * i + 2]};
        ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << "code " << codes[i];
        ASSERT_NEAR(std::sqrt(dot(v, v)), 1.0, 1e-6) << "code " << codes[i];
    }
    // Re-encode and decode again: the direction moves by no more than the round-trip bound.
    cl::Buffer db = d.input(dec), c2(d.dc.context, CL_MEM_WRITE_ONLY, n * sizeof(cl_uint)),
               o2(d.dc.context, CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
    cl::Kernel rt(d.program, "oct_roundtrip");
    rt.setArg(0, db), rt.setArg(1, c2), rt.setArg(2, o2);
    d.run(rt, n);
    std::vector<float> again = d.read<float>(o2, 3 * n);
    double worst = 0;
    for (size_t i = 0; i < n; ++i) {
        D3 a{dec[3 * i], dec[3 * i + 1], dec[3 * i + 2]}, b{again[3 * i], again[3 * i + 1], again[3 * i + 2]};
        worst = std::max(worst, std::atan2(std::sqrt(dot(cross(a, b), cross(a, b))), dot(a, b)));
    }
    EXPECT_LT(worst, 7e-5);
}

// make_frame (Duff et al. 2017) gives an orthonormal, right-handed (t x b = n) basis for every
// unit n, including both poles, the -z neighbourhood where the classic Frisvad construction
// breaks down, and signed zeros. Tolerance 2e-6: a few float ulps.
TEST(Sampling, MakeFrameIsOrthonormalEverywhere) {
    const Device& d = device();
    DirectionList normals;
    for (double s : {1.0, -1.0}) {
        normals.unit({0, 0, s}), normals.unit({s, 0, 0}), normals.unit({0, s, 0});
        for (double e : {1e-2, 1e-4, 1e-6, 1e-8, 1e-12, 1e-30})
            normals.unit({e, e, s}), normals.unit({-e, 2 * e, s}), normals.unit({e, 0, s});
        normals.unit({1, 1, s * 1e-7});
    }
    for (std::array<float, 3> v : {std::array<float, 3>{0.0f, 0.0f, -0.0f} /* invalid, skipped below */,
                                   {1.0f, 0.0f, -0.0f},
                                   {-0.0f, -0.0f, -1.0f},
                                   {-0.0f, 0.0f, 1.0f}})
        if (v[0] != 0 || v[1] != 0 || v[2] != 0) normals.exact(v);
    std::mt19937_64 g(16);
    normals.gaussian(g, 200000);
    // Normals within 1e-3 of -z, where sign(n.z) + n.z is small.
    std::uniform_real_distribution<double> tiny(-1e-3, 1e-3);
    for (int i = 0; i < 20000; ++i) normals.unit({tiny(g), tiny(g), -1});
    const size_t n = normals.size();
    cl::Buffer nb = d.input(normals.xyz), ob(d.dc.context, CL_MEM_WRITE_ONLY, 6 * n * sizeof(float));
    cl::Kernel k(d.program, "frames");
    k.setArg(0, nb), k.setArg(1, ob);
    d.run(k, n);
    std::vector<float> f = d.read<float>(ob, 6 * n);
    double worst = 0;
    size_t worst_i = 0;
    for (size_t i = 0; i < n; ++i) {
        D3 nn{normals.xyz[3 * i], normals.xyz[3 * i + 1], normals.xyz[3 * i + 2]},
            t{f[6 * i], f[6 * i + 1], f[6 * i + 2]}, b{f[6 * i + 3], f[6 * i + 4], f[6 * i + 5]};
        D3 c = cross(t, b);
        double err = std::max({std::fabs(dot(t, t) - 1), std::fabs(dot(b, b) - 1), std::fabs(dot(t, b)),
                               std::fabs(dot(t, nn)), std::fabs(dot(b, nn)), std::fabs(dot(c, nn) - 1)});
        if (!(err <= worst)) worst = err, worst_i = i; // NaN counts as worst
    }
    EXPECT_LT(worst, 2e-6) << "normal "
                           << describe({normals.xyz[3 * worst_i], normals.xyz[3 * worst_i + 1],
                                        normals.xyz[3 * worst_i + 2]});
}
