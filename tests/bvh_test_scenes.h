// The BVH test's scenes and rays (bvh_test.cpp): random soups, closed meshes seen from inside,
// shared edges and corners, exponential spacing; primary, random and edge-grazing rays. Kept
// apart from the reference and the comparison so each reads on its own.
#pragma once
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "scene/bvh_trace.h"
#include "test_util.h"

namespace clppm {
namespace {

using test::D3;
using test::d3;
using Tris = std::vector<Vec3>; // 3 per triangle

// ---- test scenes ------------------------------------------------------------------------------

std::mt19937 rng(12345);
double uniform(double a = 0, double b = 1) { return std::uniform_real_distribution<double>(a, b)(rng); }

void add_tri(Tris& t, Vec3 a, Vec3 b, Vec3 c) { t.insert(t.end(), {a, b, c}); }
Vec3 v3(double x, double y, double z) { return {float(x), float(y), float(z)}; }

Tris random_soup(int n) {
    Tris t;
    for (int i = 0; i < n; ++i) {
        const double cx = uniform(), cy = uniform(), cz = uniform(), s = uniform(0.01, 0.15);
        auto p = [&] { return v3(cx + s * uniform(-1, 1), cy + s * uniform(-1, 1), cz + s * uniform(-1, 1)); };
        add_tri(t, p(), p(), p());
    }
    return t;
}

// An icosphere: closed, every vertex bitwise shared by its triangles.
Tris icosphere(int subdivisions, double radius) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<D3> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::vector<std::array<int, 3>> next;
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back((v[a] + v[b]) * 0.5);
            return mid[key] = int(v.size()) - 1;
        };
        for (auto& t : f) {
            int a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
            next.insert(next.end(), {{t[0], a, c}, {t[1], b, a}, {t[2], c, b}, {a, b, c}});
        }
        f = next;
    }
    std::vector<Vec3> pos;
    for (D3 p : v) {
        p = p * (radius / length(p));
        pos.push_back(v3(p.x, p.y, p.z));
    }
    Tris t;
    for (auto& tri : f) add_tri(t, pos[tri[0]], pos[tri[1]], pos[tri[2]]);
    return t;
}

// The cube [-1,1]^3 with each face an n x n grid of quad pairs; grid points are computed from
// integers the same way on every face, so the cube's edges and corners are shared exactly.
Tris grid_cube(int n) {
    Tris t;
    auto c = [&](int i) { return float(-1.0 + 2.0 * i / n); };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side <= n; side += n)
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    auto p = [&](int a, int b) {
                        float q[3];
                        q[axis] = c(side);
                        q[(axis + 1) % 3] = c(a);
                        q[(axis + 2) % 3] = c(b);
                        return Vec3{q[0], q[1], q[2]};
                    };
                    add_tri(t, p(i, j), p(i + 1, j), p(i + 1, j + 1));
                    add_tri(t, p(i, j), p(i + 1, j + 1), p(i, j + 1));
                }
    return t;
}

// Coplanar triangles in z = 0 over [0,1]^2, diagonals alternating, all edges shared exactly.
Tris coplanar_grid(int n) {
    Tris t;
    auto p = [&](int i, int j) { return Vec3{float(i) / n, float(j) / n, 0.0f}; };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if ((i + j) % 2) {
                add_tri(t, p(i, j), p(i + 1, j), p(i + 1, j + 1));
                add_tri(t, p(i, j), p(i + 1, j + 1), p(i, j + 1));
            } else {
                add_tri(t, p(i, j), p(i + 1, j), p(i, j + 1));
                add_tri(t, p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            }
        }
    return t;
}

Tris transformed(const Tris& t, double scale, double offset) {
    Tris out;
    for (const Vec3& p : t) out.push_back(v3(p.x * scale + offset, p.y * scale + offset * 0.5, p.z * scale - offset));
    return out;
}

// ---- rays ---------------------------------------------------------------------------------------

D3 random_dir() {
    for (;;) {
        D3 d{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
        const double l = length(d);
        if (l > 0.1 && l <= 1) return d * (1 / l);
    }
}

// Every few rays a direction with zero components (axis-parallel or in a coordinate plane).
D3 maybe_axis_parallel(D3 d, int i) {
    switch (i % 8) {
    case 0: return {d.x > 0 ? 1.0 : -1.0, 0, 0};
    case 1: return {0, d.y > 0 ? 1.0 : -1.0, 0};
    case 2: return {0, 0, d.z > 0 ? 1.0 : -1.0};
    case 3: return d.z = 0, d * (1 / std::max(length(d), 1e-9));
    case 4: return d.x = -0.0, d * (1 / std::max(length(d), 1e-9));
    default: return d;
    }
}

TraceRay make_ray(D3 o, D3 d, double tmax = INFINITY, bool any = false) {
    return TraceRay{
        {float(o.x), float(o.y), float(o.z)}, float(tmax), {float(d.x), float(d.y), float(d.z)}, any ? 1.0f : 0.0f};
}

D3 tri_point(const Tris& t, size_t prim, double u, double v) {
    const D3 a = d3(t[3 * prim]), b = d3(t[3 * prim + 1]), c = d3(t[3 * prim + 2]);
    return a + (b - a) * u + (c - a) * v;
}

D3 tri_normal(const Tris& t, size_t prim) {
    const D3 a = d3(t[3 * prim]), n = cross(d3(t[3 * prim + 1]) - a, d3(t[3 * prim + 2]) - a);
    const double l = length(n);
    return l > 0 ? n * (1 / l) : D3{0, 0, 1};
}

struct Bounds {
    D3 lo{1e30, 1e30, 1e30}, hi{-1e30, -1e30, -1e30};
    D3 center() const { return (lo + hi) * 0.5; }
    double size() const { return length(hi - lo); }
};
Bounds bounds_of(const Tris& t) {
    Bounds b;
    for (const Vec3& p : t) {
        b.lo = {std::min(b.lo.x, double(p.x)), std::min(b.lo.y, double(p.y)), std::min(b.lo.z, double(p.z))};
        b.hi = {std::max(b.hi.x, double(p.x)), std::max(b.hi.y, double(p.y)), std::max(b.hi.z, double(p.z))};
    }
    if (t.empty()) b.lo = b.hi = {0, 0, 0};
    return b;
}

// A mix: rays from outside the bounds towards them, rays from inside, rays leaving a surface
// point with a small offset (as the renderer's bounces do), and grazing rays along a triangle.
std::vector<TraceRay> mixed_rays(const Tris& t, int n) {
    std::vector<TraceRay> rays;
    const Bounds b = bounds_of(t);
    const double size = std::max(b.size(), 1e-30);
    const size_t ntris = t.size() / 3;
    for (int i = 0; i < n; ++i) {
        const int kind = ntris ? i % 4 : i % 2;
        D3 o, d;
        if (kind == 0) { // from a sphere around the scene towards a point inside the bounds
            o = b.center() + random_dir() * size;
            D3 target{uniform(b.lo.x, b.hi.x), uniform(b.lo.y, b.hi.y), uniform(b.lo.z, b.hi.z)};
            d = target - o;
            d = d * (1 / length(d));
            if (i % 16 == 0) d = maybe_axis_parallel(d, i / 16);
        } else if (kind == 1) {             // from inside the bounds, any direction
            const double pad = 0.01 * size; // off flat bounds: a ray starting on a triangle is ill-posed
            o = {uniform(b.lo.x - pad, b.hi.x + pad), uniform(b.lo.y - pad, b.hi.y + pad),
                 uniform(b.lo.z - pad, b.hi.z + pad)};
            d = maybe_axis_parallel(random_dir(), i);
        } else { // leaving a surface
            const size_t prim = size_t(uniform(0, double(ntris))) % ntris;
            double u = uniform(), v = uniform();
            if (u + v > 1) u = 1 - u, v = 1 - v;
            D3 nrm = tri_normal(t, prim);
            if (uniform() < 0.5) nrm = nrm * -1.0;
            o = tri_point(t, prim, u, v) + nrm * (1e-4 * size);
            if (kind == 2) {
                d = random_dir();
                if (dot(d, nrm) < 0) d = d * -1.0;
            } else { // grazing: nearly in the triangle's plane
                D3 tangent = cross(nrm, random_dir());
                tangent = tangent * (1 / std::max(length(tangent), 1e-12));
                d = tangent + nrm * uniform(-1e-3, 1e-3);
            }
            if (i % 16 == 2) d = maybe_axis_parallel(d, i / 16);
        }
        rays.push_back(make_ray(o, d));
    }
    return rays;
}

} // namespace
} // namespace clppm
