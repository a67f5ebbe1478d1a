// Where a surface ends: for every triangle (BVH leaf order), which of its edges no other triangle
// continues across, and across which of the others the winding turns. kernels/disc_coverage.cl
// uses it to see, with one query of the BVH, that a gather disc lies whole on one surface (no open
// edge and no other surface within its ball) and skip measuring it with rays.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shared_types.h"

namespace clppm {

// Bit k of a triangle's entry: its edge from vertex k to vertex (k + 1) % 3 is open. Bit 3 + k: that
// edge is not open, but the triangle across it runs along it in the same direction (the two are
// wound against each other, so their normals as wound do not make one orientation of the surface).
constexpr uint8_t kOpenEdgeBit0 = 1;
constexpr uint8_t kFlippedEdgeBit0 = 8;

// Edge flags for triangles 0 .. num_tris - 1 from the traversal blocks (bvh_leaf_blocks: the
// vertices exactly as the mesh has them, so triangles that share an edge share it bit for bit).
// Vertices are matched by position across meshes (+0 and -0 alike). An edge is open unless exactly
// two triangles share it and they lie on its two sides; an edge of three or more triangles, a
// T-junction or two triangles folded onto one side is open too, which only costs the rays.
std::vector<uint8_t> open_edges(const std::vector<dev::BvhTriBlock>& blocks, size_t num_tris);

} // namespace clppm
