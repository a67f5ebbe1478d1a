// The gather disc's covered fraction (kernels/disc_coverage.cl) against a host reference that
// knows the walls of tests/data/dispersion_box_plain.gltf (floor y = -1, ceiling y = 1, walls at
// x = -1, x = 1 and z = -1, open at z = 1, a glass sphere standing on the floor), and an SPPM
// render of that box whose open edges and corners are no longer dark against the path tracer.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "device/kernel_program.h"
#include "io/image_io.h"
#include "scene/device_scene.h"
#include "scene/gltf/gltf_load.h"
#include "scene/open_edges.h"
#include "scene_builders.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

struct V3 {
    double x, y, z;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }

// kernels/sampling.cl make_frame (Duff et al. 2017).
void make_frame(V3 n, V3* t, V3* b) {
    double sign = n.z >= 0 ? 1 : -1, a = -1 / (sign + n.z), c = n.x * n.y * a;
    *t = {1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    *b = {c, sign + n.y * n.y * a, -n.y};
}

// The box as the kernel's rays see it, for a point p on the floor (n = +y) or on the back wall
// (n = +z): how far a ray in the plane runs before a wall facing another way, and whether the
// plane's own surface lies under a point (the floor ends at the open front z = 1; the back wall
// spans the box). The glass sphere neither stops the ray nor hides the floor.
double wall_distance(V3 p, V3 n, V3 d, double r) {
    double e = r;
    auto plane = [&](double pos, double dir, double at) {
        if ((at > 0 && dir > 1e-12) || (at < 0 && dir < -1e-12)) e = std::min(e, (at - pos) / dir);
    };
    plane(p.x, d.x, -1), plane(p.x, d.x, 1);
    if (n.y > 0.5) plane(p.z, d.z, -1); // the floor's disc meets the back wall
    else plane(p.y, d.y, -1), plane(p.y, d.y, 1);
    return e;
}
bool surface_under(V3 q, V3 n) {
    if (n.y > 0.5) return q.x >= -1 && q.x <= 1 && q.z >= -1 && q.z <= 1;
    return q.x >= -1 && q.x <= 1 && q.y >= -1 && q.y <= 1;
}

// disc_coverage_at written out: 8 directions rotated by u, the wall's distance or the end of the
// surface bisected below 0.9 of it, f = mean (e/R)^2 (at least 1/8) and g = sum (e/R)^4 / sum (e/R)^2.
std::array<double, 2> host_coverage(V3 p, V3 n, double r, double u) {
    V3 t, b;
    make_frame(n, &t, &b);
    double sum = 0, sum4 = 0;
    for (int k = 0; k < 8; ++k) {
        double phi = 2 * M_PI / 8 * (k + u);
        V3 d = t * std::cos(phi) + b * std::sin(phi);
        double e = wall_distance(p, n, d, r);
        if (!surface_under(p + d * (0.9 * e), n)) {
            double lo = 0, hi = 0.9 * e;
            for (int s = 0; s < 3; ++s) {
                double mid = 0.5 * (lo + hi);
                (surface_under(p + d * mid, n) ? lo : hi) = mid;
            }
            e = 0.5 * (lo + hi);
        }
        double q = (e / r) * (e / r);
        sum += q, sum4 += q * q;
    }
    return {std::max(sum / 8, 0.125), sum > 0 ? sum4 / sum : 1};
}

const char* kWrapper = R"CL(
__kernel SCALAR_WORK_ITEMS void coverage_at(SCENE_PARAMS, __global const float4* in, __global float2* out) {
    uint i = get_global_id(0);
    float4 a = in[2 * i], b = in[2 * i + 1];
    out[i] = disc_coverage_at(SCENE_ARGS, a.xyz, b.xyz, a.w, b.w);
}
)CL";

struct Query {
    V3 p, n;
    double r, u;
    const char* what;
};

} // namespace

TEST(DiscCoverage, DeviceMatchesTheHostReferenceInTheBox) {
    Scene s = load_gltf(data("dispersion_box_plain.gltf"));
    DeviceContext dc(test_device());
    DeviceScene ds = upload_scene(dc, s, RenderSettings{});
    cl::Program program = build_test_program(dc, assemble_kernel_source("disc_coverage.cl") + kWrapper);
    const V3 up{0, 1, 0}, front{0, 0, 1};
    const std::vector<Query> queries = {
        {{-0.3, -1, 0}, up, 0.2, 0.37, "the floor's middle"},
        {{-0.9, -1, 0}, up, 0.2, 0.11, "the floor by the left wall"},
        {{-0.85, -1, -0.9}, up, 0.3, 0.64, "the floor in the back left corner"},
        {{-0.5, -1, 0.92}, up, 0.2, 0.29, "the floor at its open front edge"},
        {{0.5, -1, 0.9}, up, 0.25, 0.83, "the floor's front right corner: a wall and an open edge"},
        {{0.30, -1, 0.35}, up, 0.2, 0.5, "the floor beside the glass sphere"},
        {{-0.5, -0.95, -1}, front, 0.2, 0.21, "the back wall by the floor"},
        {{0.96, 0.97, -1}, front, 0.3, 0.77, "the back wall in its top right corner"},
    };
    std::vector<cl_float4> in;
    for (const Query& q : queries) {
        in.push_back({{float(q.p.x), float(q.p.y), float(q.p.z), float(q.r)}});
        in.push_back({{float(q.n.x), float(q.n.y), float(q.n.z), float(q.u)}});
    }
    cl::Buffer inb(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, in.size() * sizeof(cl_float4), in.data());
    cl::Buffer outb(dc.context, CL_MEM_WRITE_ONLY, queries.size() * sizeof(cl_float2));
    cl::Kernel k(program, "coverage_at");
    int a = ds.set_scene_args(k);
    k.setArg(a++, inb), k.setArg(a++, outb);
    dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(queries.size()));
    std::vector<cl_float2> got(queries.size());
    dc.queue.enqueueReadBuffer(outb, CL_TRUE, 0, got.size() * sizeof(cl_float2), got.data());
    double smallest = 1;
    for (size_t i = 0; i < queries.size(); ++i) {
        const Query& q = queries[i];
        std::array<double, 2> want = host_coverage(q.p, q.n, q.r, q.u);
        EXPECT_NEAR(got[i].s[0], want[0], 2e-3) << q.what;
        EXPECT_NEAR(got[i].s[1], want[1], 2e-3) << q.what;
        smallest = std::min(smallest, want[0]);
    }
    // The cases must cut the disc, and the middle of the floor and the glass sphere must not.
    EXPECT_EQ(got[0].s[0], 1.0f);
    EXPECT_EQ(got[0].s[1], 1.0f);
    EXPECT_EQ(got[5].s[0], 1.0f) << "a transmissive surface stopped a probe";
    EXPECT_LT(smallest, 0.4);
    EXPECT_LT(got[2].s[0], got[1].s[0]) << "a corner cuts more than a wall";
}

// Half a disc by a straight open edge and a quarter in a corner: the polar sum is exact there for
// any rotation but for the bisection's resolution (0.9 R / 16 for the directions past the edge).
TEST(DiscCoverage, EdgeAndCornerFractions) {
    for (double u : {0.05, 0.3, 0.55, 0.8}) {
        std::array<double, 2> edge = host_coverage({-0.5, -1, 1 - 1e-6}, {0, 1, 0}, 0.2, u);
        EXPECT_NEAR(edge[0], 0.5, 0.01) << u;
        std::array<double, 2> corner = host_coverage({-1 + 1e-6, -1, -1 + 1e-6}, {0, 1, 0}, 0.2, u);
        EXPECT_NEAR(corner[0], 0.25, 0.13) << u; // two or three of the eight directions
    }
}

// The open front edges of the box (the image's outer ring of pixels) and its corners were dark in
// SPPM by up to half the disc. Against the path tracer, the ring's mean is now within a few per
// cent; without the coverage (--disc-coverage off, the render before) it was 12% dark.
TEST(DiscCoverage, SppmEdgesAreNotDarkAgainstThePathTracer) {
    const std::string d = make_temp_dir("disc_coverage"), scene = data("dispersion_box_plain.gltf");
    std::string out;
    const std::string common = scene + " --width 32 --height 32 --quiet --no-png --seed 3";
    ASSERT_EQ(run_clppm(common + " --integrator pt --passes 3000 -o " + d + "/pt.exr", &out), 0) << out;
    const std::string args = common + " --integrator sppm --photons 20000 --passes 96 --disc-coverage ";
    ASSERT_EQ(run_clppm(args + "auto -o " + d + "/sppm.exr", &out), 0) << out; // 1024 hit points: on
    ASSERT_EQ(run_clppm(args + "off -o " + d + "/before.exr", &out), 0) << out;
    Image pt = read_exr(d + "/pt.exr"), sppm = read_exr(d + "/sppm.exr"), before = read_exr(d + "/before.exr");
    auto ring = [](const Image& im) {
        double sum = 0;
        int n = 0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) {
                if (x > 0 && y > 0 && x < im.width - 1 && y < im.height - 1) continue;
                const size_t i = 3 * (size_t(y) * im.width + x);
                sum += im.rgb[i] + im.rgb[i + 1] + im.rgb[i + 2];
                ++n;
            }
        return sum / n;
    };
    const double now = ring(sppm) / ring(pt), was = ring(before) / ring(pt);
    std::printf("the outer ring against the path tracer: %.4f, with whole discs %.4f\n", now, was);
    EXPECT_NEAR(now, 1.0, 0.04) << "the ring's mean against the path tracer";
    EXPECT_LT(was, 0.94) << "the case must show the bias the coverage removes";
}

// auto measures the discs where the hit points number at most twice the photons per pass.
TEST(DiscCoverage, AutoWhereItCostsLittle) {
    EXPECT_TRUE(disc_coverage_wanted(DiscCoverage::Auto, 128 * 128, 200000));
    EXPECT_TRUE(disc_coverage_wanted(DiscCoverage::Auto, 512 * 512, 200000));
    EXPECT_FALSE(disc_coverage_wanted(DiscCoverage::Auto, 1024 * 1024, 200000));
    EXPECT_TRUE(disc_coverage_wanted(DiscCoverage::Auto, 400000, 200000));
    EXPECT_FALSE(disc_coverage_wanted(DiscCoverage::Auto, 400001, 200000));
    EXPECT_TRUE(disc_coverage_wanted(DiscCoverage::On, 1920 * 1080, 1000));
    EXPECT_FALSE(disc_coverage_wanted(DiscCoverage::Off, 16, 200000));
    std::string out;
    EXPECT_NE(run_clppm(std::string(CLPPM_SCENES_DIR) + "/cornell_box.gltf --disc-coverage sometimes --passes 1", &out),
              0);
    EXPECT_NE(out.find("--disc-coverage"), std::string::npos) << out;
}

namespace {

// disc_is_whole's question answered by brute force over every triangle, in double: open edges by
// an ordered map of the edges' endpoints, distances by projecting onto each triangle.
struct BruteForceScene {
    std::vector<std::array<V3, 3>> tri;
    std::vector<bool> solid;  // opaque, without alpha
    std::vector<int> open;    // bit k: edge k -> k + 1 continues into no triangle on its other side
    std::vector<int> flipped; // bit k: it does, but that triangle runs along it the same way

    explicit BruteForceScene(const Scene& s) {
        for (size_t t = 0; t < s.num_triangles(); ++t) {
            std::array<V3, 3> v;
            for (size_t k = 0; k < 3; ++k) {
                const Vec3& p = s.positions[3 * t + k];
                v[k] = {p.x, p.y, p.z};
            }
            tri.push_back(v);
            const dev::Material& m = s.materials[s.shading[t].material];
            solid.push_back(m.transmission == 0 && m.diffuse_transmission == 0 && m.alpha_mode == ALPHA_OPAQUE);
        }
        using P = std::array<double, 3>;
        std::map<std::pair<P, P>, std::vector<std::pair<size_t, int>>> edges;
        auto key = [&](size_t t, int e) {
            P a{tri[t][size_t(e)].x, tri[t][size_t(e)].y, tri[t][size_t(e)].z};
            const V3& w = tri[t][size_t((e + 1) % 3)];
            P b{w.x, w.y, w.z};
            return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
        };
        for (size_t t = 0; t < tri.size(); ++t)
            for (int e = 0; e < 3; ++e) edges[key(t, e)].push_back({t, e});
        open.assign(tri.size(), 0);
        flipped.assign(tri.size(), 0);
        for (size_t t = 0; t < tri.size(); ++t)
            for (int e = 0; e < 3; ++e) {
                const auto& uses = edges[key(t, e)];
                bool across = false, same_way = false;
                if (uses.size() == 2) {
                    const auto [u, f] = uses[0].first == t && uses[0].second == e ? uses[1] : uses[0];
                    const V3 a = tri[t][size_t(e)], b = tri[t][size_t((e + 1) % 3)], c = tri[t][size_t((e + 2) % 3)];
                    const V3 n = cross(sub(tri[t][1], tri[t][0]), sub(tri[t][2], tri[t][0]));
                    const V3 far = tri[u][size_t((f + 2) % 3)];
                    across = u != t && dot(cross(sub(b, a), sub(c, a)), n) * dot(cross(sub(b, a), sub(far, a)), n) < 0;
                    const V3 start = tri[u][size_t(f)];
                    same_way = start.x == a.x && start.y == a.y && start.z == a.z;
                }
                if (!across) open[t] |= 1 << e;
                else if (same_way) flipped[t] |= 1 << e;
            }
    }
    static V3 sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    static double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
    static V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
    static double segment_dist2(V3 p, V3 a, V3 b) {
        const V3 ab = sub(b, a);
        const double s = std::clamp(dot(sub(p, a), ab) / dot(ab, ab), 0.0, 1.0);
        const V3 d = sub(a + ab * s, p);
        return dot(d, d);
    }
    // The nearest point of the triangle: inside (by barycentrics of the projection) or on an edge.
    static double triangle_dist2(V3 p, const std::array<V3, 3>& v) {
        const V3 e1 = sub(v[1], v[0]), e2 = sub(v[2], v[0]), n = cross(e1, e2);
        const double n2 = dot(n, n), h = dot(sub(p, v[0]), n) / n2;
        const V3 q = sub(p, n * h); // p projected onto the plane
        const double b1 = dot(cross(sub(q, v[0]), e2), n) / n2, b2 = dot(cross(e1, sub(q, v[0])), n) / n2;
        if (b1 >= 0 && b2 >= 0 && b1 + b2 <= 1) return h * h * n2;
        return std::min({segment_dist2(p, v[0], v[1]), segment_dist2(p, v[1], v[2]), segment_dist2(p, v[2], v[0])});
    }
    // disc_coverage.cl's conditions written out: ball, the ball's radius over r (DISC_BALL_MARGIN);
    // flat (DISC_FLAT_HEIGHT), graph_cos, high and low (DISC_GRAPH_*), over r where a height.
    bool whole(V3 p, V3 n, double r, double ball, double flat, double graph_cos, double high, double low) const {
        const double rb2 = (ball * r) * (ball * r);
        bool found = false, all_flat = true, graph = true;
        double facing = 0;
        for (size_t t = 0; t < tri.size(); ++t) {
            if (!(triangle_dist2(p, tri[t]) <= rb2)) continue;
            if (!solid[t]) return false;
            bool near_flipped = false;
            for (int e = 0; e < 3; ++e) {
                const bool near = segment_dist2(p, tri[t][size_t(e)], tri[t][size_t((e + 1) % 3)]) <= rb2;
                if (near && (open[t] >> e & 1)) return false;
                near_flipped = near_flipped || (near && (flipped[t] >> e & 1));
            }
            const V3 nt = cross(sub(tri[t][1], tri[t][0]), sub(tri[t][2], tri[t][0]));
            const double len = std::sqrt(dot(nt, nt)), cos = dot(nt, n) / len;
            const double plane =
                std::abs(dot(sub(tri[t][0], p), nt)) / len + ball * r * std::sqrt(std::max(1 - cos * cos, 0.0));
            all_flat = all_flat && plane <= flat * r;
            double hi = -1e30, lo = 1e30;
            for (const V3& v : tri[t]) hi = std::max(hi, dot(sub(v, p), n)), lo = std::min(lo, dot(sub(v, p), n));
            if (facing == 0) facing = cos < 0 ? -1 : 1;
            graph = graph && cos * facing >= graph_cos && std::min(hi, plane) <= high * r &&
                    std::max(lo, -plane) >= -low * r && !near_flipped;
            if (!all_flat && !graph) return false;
            found = true;
        }
        return found;
    }
};

const char* kWholeWrapper = R"CL(
__kernel SCALAR_WORK_ITEMS void whole_at(SCENE_PARAMS, __global const uchar* open_edges, __global const float4* in,
                       __global int* whole, __global float2* rays) {
    uint i = get_global_id(0);
    float4 a = in[2 * i], b = in[2 * i + 1];
    whole[i] = disc_is_whole(SCENE_ARGS, open_edges, a.xyz, b.xyz, a.w) ? 1 : 0;
    rays[i] = disc_coverage_at(SCENE_ARGS, a.xyz, b.xyz, a.w, b.w);
}
)CL";

struct WholeCounts {
    int whole = 0, cut = 0, unsure = 0, whole_on_curves = 0;
};

// 600 random discs on the scene's surfaces (two thirds by area, a third by triangle: the curved
// surfaces' many facets), radii r_min to 60 r_min: the kernel's answer against brute force, and the
// rays where it says whole. curved: the material of the surfaces counted apart.
WholeCounts check_whole_query(Scene s, const std::string& what, double r_min, uint32_t curved = ~0u) {
    WholeCounts counts;
    DeviceContext dc(test_device());
    DeviceScene ds = upload_scene(dc, s, RenderSettings{}); // s now in leaf order
    const BruteForceScene brute(s);
    const size_t bytes = ds.tri_blocks_buf.getInfo<CL_MEM_SIZE>();
    std::vector<dev::BvhTriBlock> blocks(bytes / sizeof(dev::BvhTriBlock));
    dc.queue.enqueueReadBuffer(ds.tri_blocks_buf, CL_TRUE, 0, bytes, blocks.data());
    std::vector<uint8_t> open = open_edges(blocks, s.num_triangles());
    for (size_t t = 0; t < open.size(); ++t)
        EXPECT_EQ(int(open[t]), brute.open[t] | brute.flipped[t] << 3) << what << " triangle " << t;

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(0, 1);
    std::vector<double> area;
    for (const auto& v : brute.tri) {
        const V3 c = BruteForceScene::cross(BruteForceScene::sub(v[1], v[0]), BruteForceScene::sub(v[2], v[0]));
        area.push_back(std::sqrt(BruteForceScene::dot(c, c)));
    }
    std::discrete_distribution<size_t> by_area(area.begin(), area.end());
    std::uniform_int_distribution<size_t> by_index(0, brute.tri.size() - 1);
    struct Q {
        V3 p, n;
        double r, u;
        size_t tri;
    };
    std::vector<Q> qs;
    for (int i = 0; i < 600; ++i) {
        const size_t t = i % 3 == 0 ? by_index(rng) : by_area(rng);
        const auto& v = brute.tri[t];
        double b1 = uni(rng), b2 = uni(rng);
        if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
        const V3 p = v[0] + BruteForceScene::sub(v[1], v[0]) * b1 + BruteForceScene::sub(v[2], v[0]) * b2;
        V3 n = BruteForceScene::cross(BruteForceScene::sub(v[1], v[0]), BruteForceScene::sub(v[2], v[0]));
        n = n * ((uni(rng) < 0.5 ? -1 : 1) / std::sqrt(BruteForceScene::dot(n, n)));
        qs.push_back({p, n, r_min * std::pow(60.0, uni(rng)), uni(rng), t});
    }
    std::vector<cl_float4> in;
    for (const Q& q : qs) {
        in.push_back({{float(q.p.x), float(q.p.y), float(q.p.z), float(q.r)}});
        in.push_back({{float(q.n.x), float(q.n.y), float(q.n.z), float(q.u)}});
    }
    cl::Program program = build_test_program(dc, assemble_kernel_source("disc_coverage.cl") + kWholeWrapper);
    cl::Buffer inb(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, in.size() * sizeof(cl_float4), in.data());
    cl::Buffer openb(dc.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, open.size(), open.data());
    cl::Buffer wholeb(dc.context, CL_MEM_WRITE_ONLY, qs.size() * sizeof(cl_int));
    cl::Buffer raysb(dc.context, CL_MEM_WRITE_ONLY, qs.size() * sizeof(cl_float2));
    cl::Kernel k(program, "whole_at");
    int a = ds.set_scene_args(k);
    k.setArg(a++, openb), k.setArg(a++, inb), k.setArg(a++, wholeb), k.setArg(a++, raysb);
    dc.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(qs.size()));
    std::vector<cl_int> whole(qs.size());
    std::vector<cl_float2> rays(qs.size());
    dc.queue.enqueueReadBuffer(wholeb, CL_TRUE, 0, whole.size() * sizeof(cl_int), whole.data());
    dc.queue.enqueueReadBuffer(raysb, CL_TRUE, 0, rays.size() * sizeof(cl_float2), rays.data());
    for (size_t i = 0; i < qs.size(); ++i) {
        const Q& q = qs[i];
        const bool want = brute.whole(q.p, q.n, q.r, 1.02, 0.05, 0.15, 0.08, 0.2);
        // answers that a rounding of the thresholds could flip are not held against the kernel
        const double lo = 1 - 1e-3, hi = 1 + 1e-3;
        const bool sure =
            want == brute.whole(q.p, q.n, q.r, 1.02 * (1 + 1e-4), 0.05 * lo, 0.15 * hi, 0.08 * lo, 0.2 * lo) &&
            want == brute.whole(q.p, q.n, q.r, 1.02 * (1 - 1e-4), 0.05 * hi, 0.15 * lo, 0.08 * hi, 0.2 * hi);
        if (!sure) {
            ++counts.unsure;
            continue;
        }
        EXPECT_EQ(whole[i] != 0, want) << what << " query " << i << " r " << q.r;
        if (whole[i]) {
            ++counts.whole;
            counts.whole_on_curves += s.shading[q.tri].material == curved;
            EXPECT_EQ(rays[i].s[0], 1.0f) << what << " query " << i << " r " << q.r << ": the rays found a cut disc";
            EXPECT_EQ(rays[i].s[1], 1.0f) << what << " query " << i;
        } else {
            counts.cut += rays[i].s[0] < 1.0f;
        }
    }
    std::printf("%s: %d of %zu discs whole (%d on the curved surface), %d cut by the rays, %d on a threshold\n",
                what.c_str(), counts.whole, qs.size(), counts.whole_on_curves, counts.cut, counts.unsure);
    return counts;
}

} // namespace

// disc_is_whole, the one BVH query that skips the rays, against brute force over every triangle,
// and wherever it says whole, the rays it skips find exactly the whole disc: in the dispersion box
// (walls, an open front, a glass sphere) and the Cornell box at radii 0.01 to 0.6 (the boxes are 2
// wide), a finely divided sphere of radius 1 on a floor at radii 0.005 to 0.3, and the scanned blob
// of bunny_100k.gltf at radii 0.002 to 0.12, whose curved discs are whole where R is small.
TEST(DiscCoverage, TheWholeDiscQueryMatchesBruteForceAndTheRays) {
    for (const std::string& path :
         {data("dispersion_box_plain.gltf"), std::string(CLPPM_SCENES_DIR) + "/cornell_box.gltf"}) {
        const WholeCounts c = check_whole_query(load_gltf(path), path, 0.01);
        EXPECT_GT(c.whole, 100) << path; // the case must hold both answers, many times over
        EXPECT_GT(c.cut, 100) << path;
        EXPECT_LE(c.unsure, 6) << path;
    }
    Scene s;
    s.source = "<sphere on a floor>";
    const uint32_t floor = add_material(s, 0.5f, 0.5f, 0.5f), ball = add_material(s, 0.7f, 0.7f, 0.7f);
    add_quad(s, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, floor);
    add_sphere(s, {0, 1, 0}, 1.0f, 96, 192, ball);
    add_point_light(s, {0, 4, 2}, 50.f);
    const WholeCounts c = check_whole_query(s, s.source, 0.005, ball);
    EXPECT_GT(c.whole_on_curves, 100) << "curved discs must pass where they are small";
    EXPECT_LT(c.whole, 500) << "the floor's edges, where the sphere stands and larger discs are not whole";
    EXPECT_LE(c.unsure, 6);
    // a scanned blob of 100k triangles in a Cornell box, whose facets turn by several degrees
    Scene blob = load_gltf(std::string(CLPPM_SCENES_DIR) + "/bunny_100k.gltf");
    const auto named = std::find(blob.material_names.begin(), blob.material_names.end(), "blob");
    ASSERT_NE(named, blob.material_names.end());
    const uint32_t blob_material = uint32_t(named - blob.material_names.begin());
    const WholeCounts b = check_whole_query(std::move(blob), "bunny_100k.gltf", 0.002, blob_material);
    EXPECT_GT(b.whole_on_curves, 40) << "the blob's discs must pass where they are small";
    EXPECT_LE(b.unsure, 6);
}
