// The acceleration structure: a BVH_WIDTH-wide BVH built on the host with binned SAH, flattened into the
// dev::BvhNode array that kernels/bvh_traverse.cl walks, and the triangle buffer it intersects.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "shared_types.h"

namespace clppm {

struct BvhBuildResult {
    std::vector<dev::BvhNode> nodes; // nodes[0] is the root; always at least one node
    std::vector<uint32_t> tri_order; // new triangle i = input triangle tri_order[i]
    double build_seconds = 0;
    size_t leaf_count = 0;
    unsigned max_depth = 0; // of the deepest leaf, root = 1; <= BVH_MAX_DEPTH
};

// Knobs of the build; the defaults are what the renderer uses (tuned in bench/traversal_bench).
struct BvhBuildOptions {
    bool sah = true;        // false: object-median splits (the reference the tests compare with)
    unsigned max_leaf = 8;  // hard cap on triangles per leaf
    float node_cost = 1.0f; // SAH cost of visiting one node, in tests of a block of BVH_TRI_BLOCK triangles
};

// Builds the BVH over triangles given as 3 world-space positions each. Leaves reference
// contiguous ranges of the reordered triangles. Zero triangles give one root whose slots are all
// empty (never hit).
BvhBuildResult build_bvh(const std::vector<Vec3>& positions);
BvhBuildResult build_bvh(const std::vector<Vec3>& positions, const BvhBuildOptions& options);

// The triangle buffer the hit-point and light code read (kernels/scene.cl, lights.cl): 3 float4 per triangle, v0, e1 = v1 - v0, e2 = v2 - v0,
// from positions already permuted into tri_order. e1 and e2 are nudged by an ulp where that makes
// v0 + e1 == v1 and v0 + e2 == v2 exactly in float, so that the vertices the kernel reconstructs
// are bitwise the same for every triangle sharing them (watertight shared edges). v0.w holds the
// largest remaining reconstruction error (usually 0), e1.w and e2.w are 0.
std::vector<std::array<float, 4>> bvh_triangle_data(const std::vector<Vec3>& positions_in_tri_order);

// The triangle blocks bvh_intersect() tests (dev::BvhTriBlock), from positions already permuted
// into tri_order, and the nodes re-pointed at them: each leaf's child becomes ~(its first block),
// its count stays the number of triangles. Blocks follow the order of the node array.
std::vector<dev::BvhTriBlock> bvh_leaf_blocks(std::vector<dev::BvhNode>& nodes,
                                              const std::vector<Vec3>& positions_in_tri_order);

// SAH cost of a built BVH (expected cost of one ray, in units of one test of a block of
// BVH_TRI_BLOCK triangles, with a node visit costing `node_cost`): the quality measure the tests
// compare between builds.
double bvh_sah_cost(const std::vector<dev::BvhNode>& nodes, double node_cost = 1.0);

} // namespace clppm
