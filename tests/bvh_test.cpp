// The BVH (src/scene/bvh_build.cpp) and its traversal (kernels/bvh_traverse.cl, run through
// kernels/trace_rays.cl on the test device) against a brute-force double-precision reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <string>

#include "bvh_test_scenes.h"
#include "scene/bvh_build.h"
#include "scene/bvh_trace.h"
#include "test_util.h"

namespace clppm {
namespace {

// ---- the reference: double-precision Moller-Trumbore over every triangle --------------------------

// Where a ray meets one triangle's plane: t, barycentrics of v1 and v2, and how far outside the
// triangle that point is (0 inside; else the most negative barycentric, as a positive number).
struct RefHit {
    double t = -1, u = 0, v = 0, outside = 1e30, cos = 0;
    double extent = 0; // longest edge, in ray-parameter units
};

RefHit ref_triangle(const Tris& tris, size_t prim, D3 org, D3 dir) {
    const D3 v0 = d3(tris[3 * prim]), e1 = d3(tris[3 * prim + 1]) - v0, e2 = d3(tris[3 * prim + 2]) - v0;
    const D3 p = cross(dir, e2);
    const double det = dot(e1, p);
    RefHit h;
    const D3 n = cross(e1, e2);
    if (det == 0 || length(n) == 0) return h;
    const D3 s = org - v0;
    const D3 q = cross(s, e1);
    h.u = dot(s, p) / det;
    h.v = dot(dir, q) / det;
    h.t = dot(e2, q) / det;
    h.outside = std::max({0.0, -h.u, -h.v, h.u + h.v - 1.0});
    h.cos = std::fabs(dot(n, dir)) / (length(n) * length(dir));
    h.extent = std::max({length(e1), length(e2), length(e2 - e1)}) / length(dir);
    return h;
}

// Every triangle's plane hit for one ray; the comparisons below decide what counts.
std::vector<RefHit> ref_all(const Tris& tris, const TraceRay& r) {
    std::vector<RefHit> out(tris.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = ref_triangle(tris, i, d3(r.org), d3(r.dir));
    return out;
}

// ---- comparison -------------------------------------------------------------------------------

// Barycentric slack for "the ray passes this close to an edge": float traversal and the double
// reference may then disagree about which side it lands on.
constexpr double kEdgeSlack = 2e-5;

// t of the kernel against the reference: relative to t, or to the triangle's size when the hit is
// much closer than that (float vertex offsets round at the triangle's scale), and looser for
// grazing rays whose plane distance is ill-conditioned.
bool t_close(double t_kernel, const RefHit& ref) {
    return std::fabs(t_kernel - ref.t) <= 1e-5 * std::max(ref.t, ref.extent) / std::max(ref.cos, 1e-3);
}

struct Compare {
    int checked = 0, ambiguous = 0;
    std::vector<std::string> failures;
    void fail(size_t i, const TraceRay& r, const std::string& why) {
        if (failures.size() < 10) {
            char buf[512];
            std::snprintf(buf, sizeof buf, "ray %zu o=(%.9g %.9g %.9g) d=(%.9g %.9g %.9g) tmax=%g any=%g: %s", i,
                          r.org[0], r.org[1], r.org[2], r.dir[0], r.dir[1], r.dir[2], r.tmax, r.any_hit, why.c_str());
            failures.push_back(buf);
        } else if (failures.size() == 10) {
            failures.push_back("...");
        }
    }
};

// Checks one kernel result. must_hit: the ray cannot escape (inside a closed mesh, or aimed at a
// shared edge of a grid), so no edge ambiguity excuses a miss.
void check_ray(const Tris& tris, size_t i, const TraceRay& r, const TraceHit& k, bool must_hit, Compare& c) {
    const std::vector<RefHit> ref = ref_all(tris, r);
    const double tmax = r.tmax;
    const bool any = r.any_hit != 0;
    auto in_range = [&](const RefHit& h) { return h.t > 0 && h.t < tmax; };
    auto strict = [&](const RefHit& h) { return in_range(h) && h.outside == 0; };
    auto loose = [&](const RefHit& h) { return h.t > 0 && h.t < tmax * (1 + 1e-6) && h.outside <= kEdgeSlack; };
    // Borderline: within the slack of an edge, or of tmax.
    // Borderline: within the slack of an edge, of tmax, or of the origin (a ray starting on the
    // surface, which callers avoid by offsetting).
    auto self_hit = [&](const RefHit& h) { return std::fabs(h.t) <= 1e-6 * h.extent && h.outside <= kEdgeSlack; };
    auto borderline = [&](const RefHit& h) {
        if (self_hit(h)) return true;
        if (!loose(h)) return false;
        const double inner = std::min({h.u, h.v, 1 - h.u - h.v});
        return inner <= kEdgeSlack || std::fabs(h.t - tmax) <= 1e-6 * tmax;
    };
    double best = INFINITY;
    size_t best_prim = ~size_t(0);
    bool all_borderline = true;
    for (size_t p = 0; p < ref.size(); ++p) {
        if (!strict(ref[p])) continue;
        if (ref[p].t < best) best = ref[p].t, best_prim = p;
        all_borderline = all_borderline && borderline(ref[p]);
    }
    ++c.checked;
    if (!k.hit()) {
        if (best_prim == ~size_t(0)) return;
        if (all_borderline && !must_hit) {
            ++c.ambiguous;
            return;
        }
        c.fail(i, r, "missed; reference hits triangle " + std::to_string(best_prim) + " at t=" + std::to_string(best));
        return;
    }
    if (k.prim >= ref.size()) return c.fail(i, r, "hit reports triangle " + std::to_string(k.prim));
    const RefHit& h = ref[k.prim];
    if (self_hit(h) && !must_hit) {
        ++c.ambiguous;
        return;
    }
    if (!loose(h)) {
        c.fail(i, r,
               "hit triangle " + std::to_string(k.prim) + " at t=" + std::to_string(k.t) +
                   " which the reference misses (outside " + std::to_string(h.outside) + ", t " + std::to_string(h.t) +
                   ")");
        return;
    }
    if (!t_close(k.t, h)) return c.fail(i, r, "t=" + std::to_string(k.t) + " vs reference " + std::to_string(h.t));
    if (!(k.t > 0 && k.t < tmax)) return c.fail(i, r, "t out of (0, tmax)");
    if (h.outside == 0 && h.cos > 1e-2 && (std::fabs(k.u - h.u) > 1e-4 || std::fabs(k.v - h.v) > 1e-4))
        return c.fail(i, r, "barycentrics differ");
    if (any) return;
    if (best_prim == ~size_t(0) || k.prim == best_prim) return;
    // Another triangle than the reference's nearest: fine when the two are tied within 1e-6
    // (shared edges, coplanar) or the nearer one is only grazed at an edge.
    if (h.t <= best * (1 + 1e-6)) return;
    if (borderline(ref[best_prim]) && !must_hit) {
        ++c.ambiguous;
        return;
    }
    c.fail(i, r,
           "hit triangle " + std::to_string(k.prim) + " at t=" + std::to_string(h.t) + " but reference's nearest is " +
               std::to_string(best_prim) + " at t=" + std::to_string(best));
}

// ---- fixtures ---------------------------------------------------------------------------------

class BvhTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dc_ = std::make_unique<DeviceContext>(test::test_device());
        tracer_ = std::make_unique<RayTracer>(*dc_);
    }
    static void TearDownTestSuite() {
        tracer_.reset();
        dc_.reset();
    }

    // Builds, traces on the device (in the permuted order) and compares with the reference.
    void trace_and_compare(const Tris& input, std::vector<TraceRay> rays, bool must_hit, const char* what,
                           const BvhBuildOptions& options = BvhBuildOptions()) {
        const BvhBuildResult bvh = build_bvh(input, options);
        check_structure(input, bvh);
        Tris tris;
        for (uint32_t i : bvh.tri_order)
            for (int k = 0; k < 3; ++k) tris.push_back(input[3 * i + k]);
        DeviceBvh dbvh(*dc_, bvh.nodes, tris);
        Compare c;
        for (int any = 0; any < 2; ++any) {
            std::vector<TraceRay> batch = rays;
            if (any) {
                // Any-hit: half unlimited, half with tmax somewhere along the reference's nearest hit.
                const std::vector<TraceHit> closest = tracer_->trace(dbvh, rays);
                for (size_t i = 0; i < batch.size(); ++i) {
                    batch[i].any_hit = 1;
                    if (i % 2 && closest[i].hit()) batch[i].tmax = float(closest[i].t * uniform(0.3, 1.7));
                }
            }
            const std::vector<TraceHit> hits = tracer_->trace(dbvh, batch);
            for (size_t i = 0; i < batch.size(); ++i) check_ray(tris, i, batch[i], hits[i], must_hit && !any, c);
        }
        std::string all;
        for (const std::string& f : c.failures) all += f + "\n";
        EXPECT_TRUE(c.failures.empty()) << what << ": " << c.failures.size() << " failures of " << c.checked << "\n"
                                        << all;
        // Edge ambiguity must stay rare, or it would hide real misses.
        EXPECT_LE(c.ambiguous, c.checked / 200 + 2) << what;
        std::printf("%-20s %6d rays checked, %d at an edge or the origin (either answer accepted)\n", what, c.checked,
                    c.ambiguous);
    }

    // Host-side invariants of the flattened tree.
    static void check_structure(const Tris& tris, const BvhBuildResult& bvh) {
        const size_t n = tris.size() / 3;
        ASSERT_FALSE(bvh.nodes.empty());
        ASSERT_EQ(bvh.tri_order.size(), n);
        std::vector<int> seen(n, 0);
        for (uint32_t i : bvh.tri_order) {
            ASSERT_LT(i, n);
            ++seen[i];
        }
        for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "input triangle " << i;

        std::vector<int> covered(n, 0), node_refs(bvh.nodes.size(), 0);
        size_t leaves = 0;
        unsigned max_depth = 0;
        auto contains = [](const dev::BvhNode& nd, int s, const Vec3& p) {
            return p.x >= nd.bmin_x[s] && p.x <= nd.bmax_x[s] && p.y >= nd.bmin_y[s] && p.y <= nd.bmax_y[s] &&
                   p.z >= nd.bmin_z[s] && p.z <= nd.bmax_z[s];
        };
        std::vector<std::pair<int32_t, unsigned>> todo = {{0, 1}};
        node_refs[0] = 1;
        while (!todo.empty()) {
            auto [index, depth] = todo.back();
            todo.pop_back();
            max_depth = std::max(max_depth, depth);
            const dev::BvhNode& nd = bvh.nodes[size_t(index)];
            for (int s = 0; s < BVH_WIDTH; ++s) {
                if (nd.child[s] < 0) {
                    const uint32_t first = ~uint32_t(nd.child[s]);
                    if (nd.count[s] == 0) {
                        EXPECT_EQ(nd.child[s], -1) << "empty slot";
                        continue;
                    }
                    ++leaves;
                    ASSERT_LE(size_t(first) + nd.count[s], n);
                    for (uint32_t t = first; t < first + nd.count[s]; ++t) {
                        ++covered[t];
                        const uint32_t in = bvh.tri_order[t];
                        for (int k = 0; k < 3; ++k)
                            ASSERT_TRUE(contains(nd, s, tris[3 * in + k])) << "leaf bounds miss triangle " << t;
                    }
                } else {
                    ASSERT_LT(size_t(nd.child[s]), bvh.nodes.size());
                    ++node_refs[size_t(nd.child[s])];
                    const dev::BvhNode& ch = bvh.nodes[size_t(nd.child[s])];
                    for (int cs = 0; cs < BVH_WIDTH; ++cs) {
                        if (ch.child[cs] == -1 && ch.count[cs] == 0) continue;
                        const Vec3 lo{ch.bmin_x[cs], ch.bmin_y[cs], ch.bmin_z[cs]},
                            hi{ch.bmax_x[cs], ch.bmax_y[cs], ch.bmax_z[cs]};
                        ASSERT_TRUE(contains(nd, s, lo) && contains(nd, s, hi)) << "parent bounds miss a child";
                    }
                    todo.push_back({nd.child[s], depth + 1});
                }
            }
        }
        for (size_t i = 0; i < n; ++i) ASSERT_EQ(covered[i], 1) << "triangle " << i << " leaf references";
        for (size_t i = 0; i < node_refs.size(); ++i) ASSERT_EQ(node_refs[i], 1) << "node " << i << " references";
        EXPECT_EQ(leaves, bvh.leaf_count);
        EXPECT_EQ(max_depth, bvh.max_depth);
        EXPECT_LE(bvh.max_depth, unsigned(BVH_MAX_DEPTH));
    }

    static std::unique_ptr<DeviceContext> dc_;
    static std::unique_ptr<RayTracer> tracer_;
};
std::unique_ptr<DeviceContext> BvhTest::dc_;
std::unique_ptr<RayTracer> BvhTest::tracer_;

// Rays from inside a closed mesh towards `targets` or in random directions: all must hit.
std::vector<TraceRay> rays_from_inside(const Tris& /*mesh*/, double inner_radius, int n,
                                       const std::vector<D3>& targets) {
    std::vector<TraceRay> rays;
    for (int i = 0; i < n; ++i) {
        const D3 o = random_dir() * (inner_radius * uniform());
        D3 d;
        if (!targets.empty() && i % 2) {
            d = targets[size_t(uniform(0, double(targets.size()))) % targets.size()] - o;
            if (i % 4 == 1) d = d * (1 / length(d));
        } else {
            d = maybe_axis_parallel(random_dir(), i);
        }
        rays.push_back(make_ray(o, d));
    }
    return rays;
}

TEST_F(BvhTest, RandomSoup) {
    trace_and_compare(random_soup(3000), mixed_rays(random_soup(3000), 6000), false, "soup");
}

TEST_F(BvhTest, RandomSoupScaled) {
    const Tris soup = random_soup(1500);
    for (double scale : {1e-4, 1e4}) {
        const Tris t = transformed(soup, scale, 3 * scale);
        trace_and_compare(t, mixed_rays(t, 4000), false, scale < 1 ? "soup 1e-4" : "soup 1e4");
    }
}

// The default build makes leaves of at most one block; a leaf cap above BVH_TRI_BLOCK makes the
// kernel walk several blocks per leaf, which must find the same hits, watertight included.
TEST_F(BvhTest, LeavesOfSeveralBlocksTraceLikeTheReference) {
    BvhBuildOptions big;
    big.max_leaf = 2 * BVH_TRI_BLOCK + 3;
    big.node_cost = 3;
    const Tris soup = random_soup(3000), sphere = icosphere(3, 1.0);
    for (const Tris* t : {&soup, &sphere}) {
        const BvhBuildResult bvh = build_bvh(*t, big);
        size_t multi = 0;
        for (const dev::BvhNode& n : bvh.nodes)
            for (int i = 0; i < BVH_WIDTH; ++i) multi += n.child[i] < 0 && n.count[i] > BVH_TRI_BLOCK;
        EXPECT_GT(multi, 10u) << "leaves of several blocks";
    }
    trace_and_compare(soup, mixed_rays(soup, 4000), false, "soup, big leaves", big);
    std::vector<D3> targets;
    for (const Vec3& p : sphere) targets.push_back(d3(p));
    trace_and_compare(sphere, rays_from_inside(sphere, 0.5, 4000, targets), true, "sphere, big leaves", big);
}

TEST_F(BvhTest, ClosedSphereFromInside) {
    const Tris sphere = icosphere(3, 1.0);
    std::vector<D3> targets; // the sphere's vertices: where 5 or 6 triangles meet
    for (const Vec3& p : sphere) targets.push_back(d3(p));
    trace_and_compare(sphere, rays_from_inside(sphere, 0.5, 6000, targets), true, "sphere");
    trace_and_compare(sphere, mixed_rays(sphere, 2000), false, "sphere mixed");
}

TEST_F(BvhTest, ClosedCubeEdgesAndCorners) {
    const int n = 6;
    const Tris cube = grid_cube(n);
    std::vector<D3> targets; // grid vertices and edge midpoints on every face, cube edges and corners included
    for (const Vec3& p : cube) targets.push_back(d3(p));
    for (size_t i = 0; i < cube.size(); i += 3)
        for (int k = 0; k < 3; ++k) targets.push_back((d3(cube[i + k]) + d3(cube[i + (k + 1) % 3])) * 0.5);
    trace_and_compare(cube, rays_from_inside(cube, 0.9, 8000, targets), true, "cube");
    for (double scale : {1e-4, 1e4}) {
        const Tris t = transformed(cube, scale, 0);
        std::vector<D3> st;
        for (const D3& p : targets) st.push_back(p * scale);
        trace_and_compare(t, rays_from_inside(t, 0.9 * scale, 4000, st), true, scale < 1 ? "cube 1e-4" : "cube 1e4");
    }
}

TEST_F(BvhTest, CoplanarGridSharedEdges) {
    const int n = 16;
    const Tris grid = coplanar_grid(n);
    std::vector<TraceRay> rays;
    for (int r = 0; r < 8000; ++r) {
        // An interior vertex, edge midpoint or diagonal midpoint (all exact in binary).
        const int i = 1 + int(uniform(0, 2 * n - 3)), j = 1 + int(uniform(0, 2 * n - 3));
        const D3 target{i * 0.5 / n, j * 0.5 / n, 0};
        D3 o = {uniform(-0.5, 1.5), uniform(-0.5, 1.5), uniform(0.05, 1.0) * (r % 2 ? 1 : -1)};
        if (r % 5 == 0) o = {target.x, target.y, o.z}; // straight down or up: d.x = d.y = 0
        if (r % 7 == 0) o = {target.x, target.y + 0.7, o.z * 1e-3 * (r % 3 ? 1 : 10)}; // grazing, d.x = 0
        D3 d = target - o;
        if (r % 3 == 0) d = d * (1 / length(d));
        rays.push_back(make_ray(o, d));
    }
    trace_and_compare(grid, rays, true, "coplanar grid");
}

TEST_F(BvhTest, SingleTriangle) {
    Tris t;
    add_tri(t, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    trace_and_compare(t, mixed_rays(t, 2000), false, "single triangle");
    // Straight through the vertices and edges from both sides.
    std::vector<TraceRay> rays;
    for (D3 target : std::vector<D3>{{0.25, 0.25, 0}, {0.5, 0.5, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {0.1, 0.2, 0}})
        for (double z : {1.0, -1.0}) rays.push_back(make_ray({target.x, target.y, z}, {0, 0, -z}));
    const BvhBuildResult bvh = build_bvh(t);
    DeviceBvh dbvh(*dc_, bvh.nodes, t);
    const std::vector<TraceHit> hits = tracer_->trace(dbvh, rays);
    for (size_t i = 0; i < hits.size(); ++i) {
        ASSERT_TRUE(hits[i].hit()) << "ray " << i;
        EXPECT_EQ(hits[i].prim, 0u);
        EXPECT_FLOAT_EQ(hits[i].t, 1.0f);
        EXPECT_NEAR(hits[i].u, rays[i].org[0], 1e-6);
        EXPECT_NEAR(hits[i].v, rays[i].org[1], 1e-6);
    }
    // Behind the origin, at t = 0 exactly, and beyond tmax: no hit.
    std::vector<TraceRay> misses = {make_ray({0.2, 0.2, -1}, {0, 0, -1}), make_ray({0.2, 0.2, 0}, {0, 0, 1}),
                                    make_ray({0.2, 0.2, 1}, {0, 0, -1}, 0.999),
                                    make_ray({0.2, 0.2, 1}, {0, 0, -1}, 1.0),
                                    make_ray({0.2, 0.2, 1}, {0, 0, -1}, 0.5, true)};
    for (const TraceHit& h : tracer_->trace(dbvh, misses)) EXPECT_FALSE(h.hit()) << "t=" << h.t;
}

TEST_F(BvhTest, EmptyScene) {
    const BvhBuildResult bvh = build_bvh({});
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.leaf_count, 0u);
    DeviceBvh dbvh(*dc_, bvh.nodes, {});
    std::vector<TraceRay> rays;
    for (int i = 0; i < 100; ++i)
        rays.push_back(make_ray(random_dir(), maybe_axis_parallel(random_dir(), i), INFINITY, i % 2));
    for (const TraceHit& h : tracer_->trace(dbvh, rays)) {
        EXPECT_FALSE(h.hit());
        EXPECT_EQ(h.prim, ~0u);
    }
}

TEST_F(BvhTest, IdenticalCentroids) {
    // 2000 copies of one triangle, plus copies of another rotated about the same centre.
    Tris t;
    for (int i = 0; i < 1000; ++i) {
        add_tri(t, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
        add_tri(t, {-1, 0, -1}, {1, 0, -1}, {0, 0, 1});
    }
    const BvhBuildResult bvh = build_bvh(t);
    EXPECT_LE(bvh.max_depth, unsigned(BVH_MAX_DEPTH));
    trace_and_compare(t, mixed_rays(t, 500), false, "identical centroids");
}

TEST_F(BvhTest, DepthStaysBoundedOnExponentialSpacing) {
    // Triangles at x = 2^(i/8): SAH alone would build a chain; the depth cap must hold.
    Tris t;
    for (int i = 0; i < 4000; ++i) {
        const float x = float(std::ldexp(1.0, i / 8 - 250)) * (1 + (i % 8) / 8.0f);
        add_tri(t, {x, 0, 0}, {x, 1, 0}, {x, 0, 1});
    }
    const BvhBuildResult bvh = build_bvh(t);
    check_structure(t, bvh);
    EXPECT_LE(bvh.max_depth, unsigned(BVH_MAX_DEPTH));
}

TEST_F(BvhTest, SahBeatsMedianSplit) {
    for (const Tris& t : {random_soup(20000), icosphere(5, 1.0)}) {
        const double sah = bvh_sah_cost(build_bvh(t).nodes);
        BvhBuildOptions median;
        median.sah = false;
        const BvhBuildResult m = build_bvh(t, median);
        check_structure(t, m);
        const double med = bvh_sah_cost(m.nodes);
        EXPECT_LT(sah, med) << "SAH " << sah << " vs median " << med;
        std::printf("SAH cost %.2f, median-split cost %.2f (%zu triangles)\n", sah, med, t.size() / 3);
    }
}

TEST_F(BvhTest, LeafBlocksHoldEachLeafsTrianglesExactly) {
    for (const Tris& input : {random_soup(3000), icosphere(4, 1.0)}) {
        BvhBuildOptions big;
        big.max_leaf = 2 * BVH_TRI_BLOCK + 3; // leaves of 1 to 3 blocks, the last one partly filled
        big.node_cost = 3;
        for (const BvhBuildOptions& opt : {BvhBuildOptions(), big}) {
            const BvhBuildResult bvh = build_bvh(input, opt);
            Tris tris;
            for (uint32_t i : bvh.tri_order)
                for (int k = 0; k < 3; ++k) tris.push_back(input[3 * i + k]);
            std::vector<dev::BvhNode> nodes = bvh.nodes;
            const std::vector<dev::BvhTriBlock> blocks = bvh_leaf_blocks(nodes, tris);
            std::vector<int> seen(tris.size() / 3, 0);
            size_t expected_blocks = 0, multi = 0;
            for (size_t n = 0; n < nodes.size(); ++n) {
                for (int i = 0; i < BVH_WIDTH; ++i) {
                    const int32_t before = bvh.nodes[n].child[i];
                    ASSERT_EQ(nodes[n].count[i], bvh.nodes[n].count[i]);
                    if (before >= 0 || bvh.nodes[n].count[i] == 0) {
                        EXPECT_EQ(nodes[n].child[i], before) << "inner or empty slot unchanged";
                        continue;
                    }
                    const uint32_t first_tri = uint32_t(~before), count = nodes[n].count[i];
                    const uint32_t first_block = uint32_t(~nodes[n].child[i]);
                    const uint32_t nb = (count + BVH_TRI_BLOCK - 1) / BVH_TRI_BLOCK;
                    EXPECT_EQ(first_block, expected_blocks) << "blocks follow the node array";
                    expected_blocks += nb;
                    multi += nb > 1;
                    ASSERT_LE(first_block + nb, blocks.size());
                    for (uint32_t k = 0; k < nb * BVH_TRI_BLOCK; ++k) {
                        const dev::BvhTriBlock& b = blocks[first_block + k / BVH_TRI_BLOCK];
                        const uint32_t lane = k % BVH_TRI_BLOCK, t = first_tri + std::min(k, count - 1);
                        ASSERT_EQ(b.prim[lane], t) << "lane " << k << " of a leaf of " << count;
                        if (k < count) ++seen[t];
                        for (int j = 0; j < 3; ++j) {
                            const Vec3& v = tris[3 * size_t(t) + size_t(j)];
                            EXPECT_EQ(b.v[3 * j][lane], v.x); // bitwise: shared vertices stay shared
                            EXPECT_EQ(b.v[3 * j + 1][lane], v.y);
                            EXPECT_EQ(b.v[3 * j + 2][lane], v.z);
                        }
                    }
                }
            }
            EXPECT_EQ(blocks.size(), expected_blocks);
            for (size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], 1) << "triangle " << t;
            if (opt.max_leaf > BVH_TRI_BLOCK) {
                EXPECT_GT(multi, 0u) << "some leaf spans several blocks";
            }
        }
    }
}

TEST_F(BvhTest, TriangleDataReconstructsVertices) {
    // Hit points (kernels/scene.cl) recompute v1 = v0 + e1: mostly bitwise exact, else within the
    // bound in v0.w.
    for (const Tris& mesh : {icosphere(3, 1.0), transformed(icosphere(3, 1.0), 7.3, 1.7), grid_cube(5)}) {
        const auto data = bvh_triangle_data(mesh);
        size_t exact = 0, total = 0;
        for (size_t t = 0; t < mesh.size() / 3; ++t) {
            const float* v0 = data[3 * t].data();
            EXPECT_EQ(v0[0], mesh[3 * t].x);
            for (int k = 1; k < 3; ++k) {
                const float* e = data[3 * t + k].data();
                const Vec3& p = mesh[3 * t + k];
                const float r[3] = {v0[0] + e[0], v0[1] + e[1], v0[2] + e[2]};
                exact += r[0] == p.x && r[1] == p.y && r[2] == p.z;
                ++total;
                EXPECT_LE(std::fabs(r[0] - p.x), v0[3]);
                EXPECT_LE(std::fabs(r[1] - p.y), v0[3]);
                EXPECT_LE(std::fabs(r[2] - p.z), v0[3]);
                EXPECT_EQ(e[3], 0.0f);
            }
        }
        std::printf("%zu of %zu reconstructed vertices exact\n", exact, total);
    }
}

} // namespace
} // namespace clppm
