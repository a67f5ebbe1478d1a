// kernels/sobol.cl, the path tracer's Owen-scrambled Sobol' points, against a host reference that
// builds the Sobol' points from their direction numbers (Joe and Kuo's first two dimensions: the
// identity and the Pascal matrix, v_k = v_{k-1} ^ v_{k-1} >> 1) and scrambles with loops over the
// bits, then checks what the renderer relies on: every 2^m passes from a multiple of 2^m are a
// (0,m,2)-net in every 2-D draw and stratified in every 1-D draw up to SOBOL_QMC_DRAWS (later
// draws are independent numbers), the draws of one path are
// independent of one another and of other pixels', each point is uniform, and the path tracer's
// image keeps its mean while its error falls below that of independent random numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "device/kernel_program.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "stat_tests.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// ---- host reference ----

uint32_t ref_reverse(uint32_t v) {
    uint32_t r = 0;
    for (int b = 0; b < 32; ++b) r |= ((v >> b) & 1u) << (31 - b);
    return r;
}

// pbrt-v4's FastOwenScrambler hash (each output bit a function of the input bits at and below it).
uint32_t ref_owen_hash(uint32_t v, uint32_t seed) {
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return v;
}

// A nested uniform scramble of a fraction's bits (most significant first).
uint32_t ref_owen(uint32_t x, uint32_t seed) { return ref_reverse(ref_owen_hash(ref_reverse(x), seed)); }

// Sobol' dimension d (0 or 1) of index i, as a 32-bit fraction, from the direction numbers.
uint32_t ref_sobol(uint32_t i, int d) {
    uint32_t v = 0x80000000u, x = 0;
    for (int k = 0; k < 32; ++k) {
        if ((i >> k) & 1u) x ^= v;
        v = d == 0 ? v >> 1 : v ^ (v >> 1);
    }
    return x;
}

uint32_t ref_hash32(uint32_t x) { // Wellons' lowbias32
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    return x ^ (x >> 16);
}

// SOBOL_QMC_DRAWS in kernels/sobol.cl: the draws of a path that are Sobol' points.
constexpr uint32_t kQmcDraws = 10;

struct RefSobol {
    uint32_t seed;
    uint32_t index;
    uint32_t dim = 0;
    RefSobol(uint64_t render_seed, uint32_t pixel, uint64_t pass)
        : seed(uint32_t(ref_splitmix64(render_seed ^ ref_splitmix64(uint64_t(pixel) + 0x632BE59BD9B4E019ull)))),
          index(uint32_t(pass)) {}
    // The screen-space layout of 2^l planned passes (sobol_make_screen): pixel (x, y)'s pass j is
    // point morton(x, y) 2^l + j of one sequence; the index's bits above 32 and the generation
    // j / 2^l choose its scrambles.
    static RefSobol screen(uint64_t render_seed, uint32_t x, uint32_t y, uint64_t pass, uint32_t l) {
        uint64_t morton = 0;
        for (int b = 0; b < 32; ++b)
            morton |= (uint64_t(x >> b & 1u) << (2 * b)) | (uint64_t(y >> b & 1u) << (2 * b + 1));
        const uint64_t low = l == 64 ? pass : pass & ((uint64_t(1) << l) - 1);
        const uint64_t index = (morton << l) | low;
        const uint64_t key = (index >> 32) ^ ((pass >> l) * 0xD1B54A32D192ED03ull);
        RefSobol r(0, 0, 0);
        r.seed = uint32_t(ref_splitmix64(render_seed ^ ref_splitmix64(key + 0x2545F4914F6CDD1Dull)));
        r.index = uint32_t(index);
        return r;
    }
    // Burley 2020's shuffle: a nested uniform scramble of the index's reversed bits.
    uint32_t shuffled(uint32_t* sx, uint32_t* sy) {
        const uint32_t h = ref_hash32(seed + dim++ * 0x9E3779B9u);
        *sx = ref_hash32(h ^ 0x85EBCA6Bu), *sy = ref_hash32(h ^ 0xC2B2AE35u);
        return ref_reverse(ref_owen_hash(ref_reverse(index), h));
    }
    static float to_float(uint32_t x) { return float(x >> 8) * (1.0f / 16777216.0f); }
    // Past kQmcDraws: independent numbers, hash32 of (seed, draw) and the pass, hashed again.
    std::array<float, 2> plain() {
        const uint32_t h = ref_hash32(seed + dim++ * 0x9E3779B9u) ^ ref_reverse(index);
        return {to_float(ref_hash32(h ^ 0x85EBCA6Bu)), to_float(ref_hash32(h ^ 0xC2B2AE35u))};
    }
    float get1() {
        if (dim >= kQmcDraws) return plain()[0];
        uint32_t sx, sy;
        const uint32_t i = shuffled(&sx, &sy);
        return to_float(ref_owen(ref_sobol(i, 0), sx));
    }
    std::array<float, 2> get2() {
        if (dim >= kQmcDraws) return plain();
        uint32_t sx, sy;
        const uint32_t i = shuffled(&sx, &sy);
        return {to_float(ref_owen(ref_sobol(i, 0), sx)), to_float(ref_owen(ref_sobol(i, 1), sy))};
    }
};

// A path's draws in the path tracer's pattern: 2-D, 2-D, then per bounce 1-D, 2-D, 1-D, 2-D, 1-D.
bool draw_is_2d(uint32_t k) { return k < 2 || ((k - 2) % 5 == 1) || ((k - 2) % 5 == 3); }

const char* kWrappers = R"CL(
/* Work item i's draws in the path tracer's pattern, 2 floats each (the second 0 for a 1-D draw). */
void write_draws(Sobol* s, uint i, uint draws, __global float* out) {
    for (uint k = 0; k < draws; ++k) {
        bool two = k < 2 || (k - 2) % 5 == 1 || (k - 2) % 5 == 3;
        float2 u = two ? sobol_2d(s) : (float2)(sobol_1d(s), 0.0f);
        out[((size_t)i * draws + k) * 2] = u.x;
        out[((size_t)i * draws + k) * 2 + 1] = u.y;
    }
}

/* For work item i = (pixel - first_pixel) * passes + j: pass first_pass + j of pixel, `draws`
 * draws in the path tracer's pattern, 2 floats each (the second 0 for a 1-D draw). */
__kernel void draws(ulong seed, uint first_pixel, ulong first_pass, uint passes, uint draws, __global float* out) {
    uint i = get_global_id(0);
    uint pixel = first_pixel + i / passes;
    Sobol s = sobol_make(seed, pixel, first_pass + i % passes);
    write_draws(&s, i, draws, out);
}
)CL";

const char* kScreenWrappers = R"CL(
/* The same for the screen-space layout of 2^l passes: work item i is pass first_pass + i % passes
 * of pixel (x0 + q % w, y0 + q / w), q = i / passes. */
__kernel void screen_draws(ulong seed, uint x0, uint y0, uint w, uint l, ulong first_pass, uint passes, uint draws,
                           __global float* out) {
    uint i = get_global_id(0), q = i / passes;
    Sobol s = sobol_make_screen(seed, x0 + q % w, y0 + q / w, first_pass + i % passes, l);
    write_draws(&s, i, draws, out);
}
)CL";

struct Device : KernelHarness {
    Device() : KernelHarness(assemble_kernel_source("sobol.cl") + kWrappers + kScreenWrappers) {}
    // out[((p * passes + j) * draws + k) * 2 + c]
    std::vector<float> draws(uint64_t seed, uint32_t first_pixel, uint32_t pixels, uint64_t first_pass, uint32_t passes,
                             uint32_t draws) const {
        const size_t n = size_t(pixels) * passes;
        cl::Buffer ob = output(n * draws * 2 * sizeof(float));
        cl::Kernel k(program, "draws");
        k.setArg(0, cl_ulong(seed)), k.setArg(1, cl_uint(first_pixel)), k.setArg(2, cl_ulong(first_pass));
        k.setArg(3, cl_uint(passes)), k.setArg(4, cl_uint(draws)), k.setArg(5, ob);
        run(k, n);
        return read<float>(ob, n * draws * 2);
    }
    // The w x h pixels from (x0, y0), screen-space layout of 2^l passes; the same order.
    std::vector<float> screen_draws(uint64_t seed, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h, uint32_t l,
                                    uint64_t first_pass, uint32_t passes, uint32_t draws) const {
        const size_t n = size_t(w) * h * passes;
        cl::Buffer ob = output(n * draws * 2 * sizeof(float));
        cl::Kernel k(program, "screen_draws");
        k.setArg(0, cl_ulong(seed)), k.setArg(1, cl_uint(x0)), k.setArg(2, cl_uint(y0)), k.setArg(3, cl_uint(w));
        k.setArg(4, cl_uint(l)), k.setArg(5, cl_ulong(first_pass)), k.setArg(6, cl_uint(passes));
        k.setArg(7, cl_uint(draws)), k.setArg(8, ob);
        run(k, n);
        return read<float>(ob, n * draws * 2);
    }
};

const Device& device() {
    static Device d;
    return d;
}

// Whether the 2^m points (x, y) put one point in every elementary interval of every shape
// 2^-a x 2^-(m-a).
bool is_net(const std::vector<std::array<float, 2>>& pts, int m, std::string* why) {
    for (int a = 0; a <= m; ++a) {
        std::vector<int> count(size_t(1) << m, 0);
        for (const auto& p : pts) {
            const uint32_t cx = uint32_t(double(p[0]) * double(1u << a));
            const uint32_t cy = uint32_t(double(p[1]) * double(1u << (m - a)));
            ++count[(cy << a) | cx];
        }
        for (size_t c = 0; c < count.size(); ++c)
            if (count[c] != 1) {
                *why = "shape 2^-" + std::to_string(a) + " x 2^-" + std::to_string(m - a) + ": cell " +
                       std::to_string(c) + " holds " + std::to_string(count[c]) + " points";
                return false;
            }
    }
    return true;
}

} // namespace

// The direction-number reference agrees with the closed forms it stands for: van der Corput is
// the reversed index, and the second dimension's first points are the published ones (Joe and
// Kuo's dimension 2 as scipy.stats.qmc.Sobol lists it, 0 .5 .25 .75 .375 .875 .125 .625, is in
// Gray-code order; index i here is its point gray(i) = i ^ i >> 1 there).
TEST(Sobol, HostReferenceMatchesPublishedPoints) {
    const double gray_order[8] = {0, 0.5, 0.25, 0.75, 0.375, 0.875, 0.125, 0.625};
    double dim1[8];
    for (uint32_t g = 0; g < 8; ++g) dim1[g ^ (g >> 1)] = gray_order[g];
    for (uint32_t i = 0; i < 8; ++i) {
        EXPECT_EQ(ref_sobol(i, 0), ref_reverse(i));
        EXPECT_EQ(double(ref_sobol(i, 1)) / 4294967296.0, dim1[i]) << "index " << i;
    }
}

// The device's points equal the host reference bit for bit, at extreme seeds and passes.
TEST(Sobol, DeviceMatchesHostReferenceBitForBit) {
    const Device& d = device();
    const uint32_t draws = 17, passes = 64, pixels = 16;
    const uint64_t seeds[] = {0, 1, 0xffffffffffffffffull};
    const uint64_t first_passes[] = {0, 1000, 0xffffffffull - 10, 0x100000000ull};
    size_t mismatches = 0, checked = 0;
    for (uint64_t seed : seeds)
        for (uint64_t fp : first_passes) {
            const std::vector<float> got = d.draws(seed, 1234567, pixels, fp, passes, draws);
            for (uint32_t p = 0; p < pixels; ++p)
                for (uint32_t j = 0; j < passes; ++j) {
                    RefSobol r(seed, 1234567 + p, fp + j);
                    for (uint32_t k = 0; k < draws; ++k) {
                        const size_t o = ((size_t(p) * passes + j) * draws + k) * 2;
                        std::array<float, 2> u = draw_is_2d(k) ? r.get2() : std::array<float, 2>{r.get1(), 0.f};
                        mismatches += got[o] != u[0] || got[o + 1] != u[1];
                        EXPECT_TRUE(got[o] >= 0.f && got[o] < 1.f && got[o + 1] >= 0.f && got[o + 1] < 1.f);
                        ++checked;
                    }
                }
        }
    EXPECT_EQ(mismatches, 0u) << "of " << checked;
}

// Any 2^m passes from a multiple of 2^m: every 2-D draw is a (0,m,2)-net, every 1-D draw has one
// point in each interval of length 2^-m, up to the last Sobol' draw. This is what the samples
// gain over random ones; a broken shuffle or scramble breaks it.
TEST(Sobol, AlignedBlocksOfPassesAreNets) {
    const Device& d = device();
    const int m = 8;
    const uint32_t n = 1u << m, draws = kQmcDraws, pixels = 3;
    for (uint64_t block : {uint64_t(0), uint64_t(5), uint64_t(1000)}) {
        const std::vector<float> got = d.draws(42, 77, pixels, block * n, n, draws);
        for (uint32_t p = 0; p < pixels; ++p)
            for (uint32_t k = 0; k < draws; ++k) {
                std::vector<std::array<float, 2>> pts;
                std::vector<int> strata(n, 0);
                for (uint32_t j = 0; j < n; ++j) {
                    const size_t o = ((size_t(p) * n + j) * draws + k) * 2;
                    pts.push_back({got[o], got[o + 1]});
                    ++strata[size_t(double(got[o]) * n)];
                }
                std::string why;
                if (draw_is_2d(k)) {
                    EXPECT_TRUE(is_net(pts, m, &why)) << "block " << block << " draw " << k << ": " << why;
                }
                for (uint32_t c = 0; c < n; ++c)
                    ASSERT_EQ(strata[c], 1) << "block " << block << " draw " << k << " stratum " << c;
            }
    }
    // A block that is not aligned is no net, nor is the first draw past the Sobol' ones: the
    // property is the points', not the test's.
    const std::vector<float> off = d.draws(42, 77, 1, 3, n, 1);
    std::vector<int> strata(n, 0);
    for (uint32_t j = 0; j < n; ++j) ++strata[size_t(double(off[2 * j]) * n)];
    EXPECT_NE(std::count(strata.begin(), strata.end(), 1), int(n));
    const std::vector<float> past = d.draws(42, 77, 1, 0, n, kQmcDraws + 1);
    std::vector<int> past_strata(n, 0);
    for (uint32_t j = 0; j < n; ++j)
        ++past_strata[size_t(double(past[(size_t(j) * (kQmcDraws + 1) + kQmcDraws) * 2]) * n)];
    EXPECT_NE(std::count(past_strata.begin(), past_strata.end(), 1), int(n));
}

// The draws of one path are independent of one another (the padding), and pixels of one another:
// over 4096 passes, the joint histogram of two draws passes a chi-square test and their
// correlation is that of independent numbers; without the per-draw shuffle, draws 2 and 4 of
// these paths would fall in the same half together every time.
TEST(Sobol, DrawsAndPixelsAreIndependent) {
    const Device& d = device();
    const uint32_t n = 4096, draws = 12;
    const std::vector<float> got = d.draws(9, 500, 2, 0, n, draws);
    auto coord = [&](uint32_t p, uint32_t j, uint32_t k, int c) {
        return double(got[((size_t(p) * n + j) * draws + k) * 2 + c]);
    };
    const int cells = 16;
    const double alpha = sidak(1e-3, 12);
    for (uint32_t k = 0; k + 1 < draws; ++k) {
        for (auto [pa, ka, pb, kb] : {std::array<uint32_t, 4>{0, k, 0, k + 1}, std::array<uint32_t, 4>{0, k, 1, k}}) {
            std::vector<double> obs(cells * cells, 0.0), expd(cells * cells, double(n) / (cells * cells));
            std::vector<double> a, b;
            for (uint32_t j = 0; j < n; ++j) {
                const double x = coord(pa, j, ka, 0), y = coord(pb, j, kb, 0);
                obs[size_t(y * cells) * cells + size_t(x * cells)] += 1;
                a.push_back(x), b.push_back(y);
            }
            const Chi2Result r = chi2_test(obs, expd);
            EXPECT_GT(r.p_value, alpha) << "pixel " << pa << " draw " << ka << " against pixel " << pb << " draw "
                                        << kb;
            EXPECT_LT(std::fabs(correlation(a, b)), 4.0 / std::sqrt(double(n)));
        }
    }
}

// The screen-space layout's points equal the host reference bit for bit: at the largest
// coordinates, at L = 0 and L = 32, and past the planned passes (a new generation).
TEST(Sobol, ScreenLayoutMatchesHostReferenceBitForBit) {
    const Device& d = device();
    const uint32_t draws = 13, passes = 8;
    struct Case {
        uint64_t seed;
        uint32_t x0, y0, l;
        uint64_t first_pass;
    };
    const Case cases[] = {{1, 0, 0, 3, 0},
                          {0xffffffffffffffffull, 65532, 65534, 5, 30},
                          {7, 1000, 3, 0, 5},
                          {9, 65534, 0, 32, 0xffffffffull - 3},
                          {3, 12, 40, 2, 0x100000000ull + 1}};
    size_t mismatches = 0, checked = 0;
    for (const Case& c : cases) {
        const uint32_t w = 2, h = 2;
        const std::vector<float> got = d.screen_draws(c.seed, c.x0, c.y0, w, h, c.l, c.first_pass, passes, draws);
        for (uint32_t q = 0; q < w * h; ++q)
            for (uint32_t j = 0; j < passes; ++j) {
                RefSobol r = RefSobol::screen(c.seed, c.x0 + q % w, c.y0 + q / w, c.first_pass + j, c.l);
                for (uint32_t k = 0; k < draws; ++k) {
                    const size_t o = ((size_t(q) * passes + j) * draws + k) * 2;
                    std::array<float, 2> u = draw_is_2d(k) ? r.get2() : std::array<float, 2>{r.get1(), 0.f};
                    mismatches += got[o] != u[0] || got[o + 1] != u[1];
                    ++checked;
                }
            }
    }
    EXPECT_EQ(mismatches, 0u) << "of " << checked;
}

// What the layout is for: with 2^l planned passes, each pixel's passes are a net as before, and so
// are all the points of an aligned 2^k x 2^k block of pixels together (4^k 2^l of them), in every
// Sobol' draw; the passes of the next generation again. A block that is not aligned is no net.
TEST(Sobol, ScreenLayoutMakesAlignedBlocksOfPixelsNets) {
    const Device& d = device();
    const uint32_t l = 4, passes = 1u << l, side = 4, draws = kQmcDraws;
    auto block_points = [&](const std::vector<float>& got, uint32_t k, uint32_t x, uint32_t y, uint32_t s,
                            uint32_t stride) {
        std::vector<std::array<float, 2>> pts;
        for (uint32_t py = y; py < y + s; ++py)
            for (uint32_t px = x; px < x + s; ++px)
                for (uint32_t j = 0; j < passes; ++j) {
                    const size_t o = (((size_t(py) * stride + px) * passes + j) * draws + k) * 2;
                    pts.push_back({got[o], got[o + 1]});
                }
        return pts;
    };
    auto strata_ok = [](const std::vector<std::array<float, 2>>& pts) {
        std::vector<int> strata(pts.size(), 0);
        for (const auto& p : pts) ++strata[size_t(double(p[0]) * double(pts.size()))];
        return std::count(strata.begin(), strata.end(), 1) == int(pts.size());
    };
    for (uint64_t generation : {uint64_t(0), uint64_t(3)}) {
        const std::vector<float> got =
            d.screen_draws(5, 8, 12, side, side, l, generation * passes, passes, draws); // (8, 12): aligned
        for (uint32_t k = 0; k < draws; ++k) {
            std::string why;
            for (uint32_t s : {1u, 2u, 4u})
                for (uint32_t y = 0; y < side; y += s)
                    for (uint32_t x = 0; x < side; x += s) {
                        const auto pts = block_points(got, k, x, y, s, side);
                        const int m = int(l) + 2 * (s == 1 ? 0 : s == 2 ? 1 : 2);
                        if (draw_is_2d(k)) {
                            EXPECT_TRUE(is_net(pts, m, &why))
                                << "generation " << generation << " draw " << k << ", " << s << "x" << s
                                << " pixels at " << x << "," << y << ": " << why;
                        }
                        EXPECT_TRUE(strata_ok(pts)) << "draw " << k << ", " << s << "x" << s << " at " << x << "," << y;
                    }
        }
    }
    // The same pixels' blocks seen one pixel to the right straddle two aligned blocks.
    const std::vector<float> off = d.screen_draws(5, 9, 12, side, side, l, 0, passes, 1);
    std::vector<std::array<float, 2>> pts;
    for (uint32_t q = 0; q < side * side; ++q)
        for (uint32_t j = 0; j < passes; ++j) pts.push_back({off[(q * passes + j) * 2], off[(q * passes + j) * 2 + 1]});
    std::string why;
    EXPECT_FALSE(is_net(pts, int(l) + 4, &why));
}

// What the points are for: integrating a disc's indicator (an edge, as a shadow or a silhouette)
// over the unit square with 1024 points, the root-mean-square error over 256 pixels' independent
// randomisations is at most a third of Monte Carlo's sqrt(p (1 - p) / N), and the mean is
// unbiased.
TEST(Sobol, IntegratesAnEdgeFasterThanRandomNumbers) {
    const Device& d = device();
    const uint32_t n = 1024, pixels = 256;
    const std::vector<float> got = d.draws(3, 0, pixels, 0, n, 1);
    const double p = M_PI * 0.3 * 0.3; // a disc of radius 0.3 about (0.5, 0.5)
    double sq = 0, mean = 0;
    for (uint32_t px = 0; px < pixels; ++px) {
        double hits = 0;
        for (uint32_t j = 0; j < n; ++j) {
            const double x = got[(px * n + j) * 2] - 0.5, y = got[(px * n + j) * 2 + 1] - 0.5;
            hits += x * x + y * y < 0.09;
        }
        const double e = hits / n - p;
        sq += e * e, mean += e;
    }
    const double rmse = std::sqrt(sq / pixels), mc = std::sqrt(p * (1 - p) / n);
    EXPECT_LT(rmse, mc / 3) << "Sobol' RMSE " << rmse << ", Monte Carlo " << mc;
    EXPECT_LT(std::fabs(mean / pixels), 3 * rmse / std::sqrt(double(pixels)));
}

// The path tracer with Sobol' points on a diffuse Cornell box (the scene issue 36 measured it on),
// against a long independent-number render: the same mean, and at equal passes a lower error than
// the same render with independent numbers.
TEST(Sobol, PathTracerKeepsTheMeanAndLowersTheError) {
    nlohmann::json box = nlohmann::json::parse(slurp(std::string(CLPPM_SCENES_DIR) + "/cornell_box.gltf"));
    auto& nodes = box["scenes"][0]["nodes"];
    nlohmann::json kept = nlohmann::json::array();
    for (const auto& n : nodes) {
        const std::string name = box["nodes"][n.get<int>()].value("name", "");
        if (name != "glass_sphere" && name != "mirror_sphere") kept.push_back(n);
    }
    ASSERT_EQ(kept.size() + 2, nodes.size());
    nodes = kept;
    const std::string file = make_temp_dir("sobol") + "/cornell_diffuse.gltf";
    std::ofstream(file) << box.dump();
    const Scene scene = load_gltf(file);

    RenderSettings s;
    s.integrator = "pt";
    s.width = s.height = 24;
    s.sampler = Sampler::Independent;
    s.seed = 99;
    const Image ref = render_passes(scene, s, 16384);
    s.seed = 1;
    const Image independent = render_passes(scene, s, 256);
    s.sampler = Sampler::Sobol;
    const Image sobol = render_passes(scene, s, 256);
    const ImageDifference di = compare_images(independent, ref), ds = compare_images(sobol, ref);
    EXPECT_NEAR(ds.mean_a / ds.mean_b, 1.0, 0.005);
    EXPECT_LT(ds.rel_mse, 0.8 * di.rel_mse) << "Sobol' " << ds.rel_mse << ", independent " << di.rel_mse;
    // Laid out on the screen: the same mean, and per pixel the same error as each pixel's own
    // sequence (what it gains is across pixels: ScreenLayoutMakesAlignedBlocksOfPixelsNets).
    s.sampler = Sampler::ZSobol;
    s.planned_passes = 256;
    const ImageDifference dz = compare_images(render_passes(scene, s, 256), ref);
    EXPECT_NEAR(dz.mean_a / dz.mean_b, 1.0, 0.005);
    EXPECT_LT(dz.rel_mse, 0.8 * di.rel_mse) << "zsobol " << dz.rel_mse << ", independent " << di.rel_mse;
}
