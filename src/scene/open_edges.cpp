#include "scene/open_edges.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <unordered_map>

namespace clppm {

namespace {

using Vertex = std::array<float, 3>;
using Triangle = std::array<Vertex, 3>;

// Bit pattern of a coordinate, -0 as +0.
uint32_t coordinate_bits(float f) {
    if (f == 0.0f) f = 0.0f;
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

using EdgeKey = std::array<uint32_t, 6>; // the endpoints' bits, the smaller endpoint first

EdgeKey edge_key(const Triangle& t, int e) {
    std::array<uint32_t, 3> a{}, b{};
    for (size_t k = 0; k < 3; ++k) {
        a[k] = coordinate_bits(t[size_t(e)][k]);
        b[k] = coordinate_bits(t[size_t((e + 1) % 3)][k]);
    }
    if (b < a) std::swap(a, b);
    return {a[0], a[1], a[2], b[0], b[1], b[2]};
}

struct EdgeKeyHash {
    size_t operator()(const EdgeKey& k) const {
        uint64_t h = 1469598103934665603ull; // FNV-1a over the six words
        for (uint32_t w : k) h = (h ^ w) * 1099511628211ull;
        return size_t(h ^ (h >> 29));
    }
};

struct EdgeUses {
    int count = 0;
    uint32_t use[2] = {0, 0}; // the first two uses, as 3 triangle + edge
};

using D3 = std::array<double, 3>;
D3 sub(const Vertex& a, const Vertex& b) { return {double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]}; }
D3 cross(const D3& a, const D3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Whether triangle u's neighbour across edge e (use v) continues the surface: its far vertex lies
// on the other side of the edge from u's own, seen along u's normal. Two triangles folded onto the
// same side share the edge but leave the other side open.
bool continues(const std::vector<Triangle>& tri, uint32_t u, uint32_t v) {
    const Triangle& A = tri[u / 3];
    const Triangle& B = tri[v / 3];
    const int ea = int(u % 3), eb = int(v % 3);
    if (u / 3 == v / 3) return false;
    const Vertex& a = A[size_t(ea)];
    const D3 n = cross(sub(A[1], A[0]), sub(A[2], A[0]));
    const D3 edge = sub(A[size_t((ea + 1) % 3)], a);
    const double own = dot(cross(edge, sub(A[size_t((ea + 2) % 3)], a)), n);
    const double other = dot(cross(edge, sub(B[size_t((eb + 2) % 3)], a)), n);
    return own * other < 0;
}

// Whether triangles u and v (uses as 3 triangle + edge) run along their shared edge in the same
// direction: u's edge starts where v's does.
bool same_direction(const std::vector<Triangle>& tri, uint32_t u, uint32_t v) {
    const Vertex& a = tri[u / 3][u % 3];
    const Vertex& b = tri[v / 3][v % 3];
    for (size_t k = 0; k < 3; ++k)
        if (coordinate_bits(a[k]) != coordinate_bits(b[k])) return false;
    return true;
}

} // namespace

std::vector<uint8_t> open_edges(const std::vector<dev::BvhTriBlock>& blocks, size_t num_tris) {
    std::vector<Triangle> tri(num_tris);
    std::vector<bool> seen(num_tris, false);
    for (const dev::BvhTriBlock& b : blocks)
        for (int lane = 0; lane < BVH_TRI_BLOCK; ++lane) {
            const uint32_t p = b.prim[lane];
            if (p >= num_tris || seen[p]) continue; // a leaf's last block repeats its last triangle
            seen[p] = true;
            for (size_t j = 0; j < 3; ++j)
                for (size_t k = 0; k < 3; ++k) tri[p][j][k] = b.v[3 * j + k][lane];
        }
    std::unordered_map<EdgeKey, EdgeUses, EdgeKeyHash> uses;
    uses.reserve(num_tris * 2);
    for (uint32_t t = 0; t < num_tris; ++t)
        for (int e = 0; seen[t] && e < 3; ++e) {
            EdgeUses& u = uses[edge_key(tri[t], e)];
            if (u.count < 2) u.use[u.count] = 3 * t + uint32_t(e);
            ++u.count;
        }
    std::vector<uint8_t> open(num_tris, 0);
    for (uint32_t t = 0; t < num_tris; ++t) {
        if (!seen[t]) open[t] = 7 * kOpenEdgeBit0; // not in any block: claim nothing of it
        for (int e = 0; seen[t] && e < 3; ++e) {
            const EdgeUses& u = uses.at(edge_key(tri[t], e));
            const uint32_t self = 3 * t + uint32_t(e);
            const uint32_t other = u.use[0] == self ? u.use[1] : u.use[0];
            const bool closed = u.count == 2 && continues(tri, self, other);
            if (!closed) open[t] |= uint8_t(kOpenEdgeBit0 << e);
            else if (same_direction(tri, self, other)) open[t] |= uint8_t(kFlippedEdgeBit0 << e);
        }
    }
    return open;
}

} // namespace clppm
