// Which triangle edges a surface ends at (src/scene/open_edges.cpp), on hand-made blocks.
#include <gtest/gtest.h>

#include <array>

#include "scene/open_edges.h"

using namespace clppm;

namespace {

using Tri = std::array<std::array<float, 3>, 3>;

// Triangles into traversal blocks as bvh_leaf_blocks lays them out; the last block repeats its
// last triangle in unused lanes.
std::vector<dev::BvhTriBlock> blocks_of(const std::vector<Tri>& tris) {
    std::vector<dev::BvhTriBlock> blocks((tris.size() + BVH_TRI_BLOCK - 1) / BVH_TRI_BLOCK);
    for (size_t b = 0; b < blocks.size(); ++b)
        for (size_t lane = 0; lane < BVH_TRI_BLOCK; ++lane) {
            const size_t t = std::min(b * BVH_TRI_BLOCK + lane, tris.size() - 1);
            blocks[b].prim[lane] = uint32_t(t);
            for (size_t j = 0; j < 3; ++j)
                for (size_t k = 0; k < 3; ++k) blocks[b].v[3 * j + k][lane] = tris[t][j][k];
        }
    return blocks;
}

} // namespace

// A square of two triangles: its four sides are open, the diagonal they share is not.
TEST(OpenEdges, ASquareIsOpenOnlyAtItsSides) {
    const std::vector<Tri> square = {Tri{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}}, Tri{{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}}};
    const std::vector<uint8_t> open = open_edges(blocks_of(square), 2);
    ASSERT_EQ(open.size(), 2u);
    EXPECT_EQ(open[0], 1 | 2) << "edges (0,0)-(1,0) and (1,0)-(1,1) open, the diagonal closed";
    EXPECT_EQ(open[1], 2 | 4) << "edges (1,1)-(0,1) and (0,1)-(0,0) open, the diagonal closed";
}

// Vertices are matched by position across meshes and signs of zero; a fold onto one side, an edge of
// three triangles and a T-junction all leave the edge open.
TEST(OpenEdges, WhatCountsAsContinued) {
    // two meshes, the second with -0 where the first has 0, meeting at x = 0 (a flat floor)
    const std::vector<Tri> welded = {Tri{{{-1, 0, 0}, {0, 0, 0}, {0, 0, 1}}},
                                     Tri{{{-0.0f, 0, 1}, {0, -0.0f, 0}, {1, 0, 0.5f}}}};
    std::vector<uint8_t> open = open_edges(blocks_of(welded), 2);
    EXPECT_EQ(open[0], 1 | 4) << "the shared edge (0,0,0)-(0,0,1) is closed";
    EXPECT_EQ(open[1], 2 | 4);
    // the second triangle wound the other way: the edge still continues the surface, but flipped
    const std::vector<Tri> rewound = {welded[0], Tri{{{0, -0.0f, 0}, {-0.0f, 0, 1}, {1, 0, 0.5f}}}};
    open = open_edges(blocks_of(rewound), 2);
    EXPECT_EQ(open[0], 1 | 4 | (kFlippedEdgeBit0 << 1));
    EXPECT_EQ(open[1], 2 | 4 | kFlippedEdgeBit0);
    // the same second triangle folded back onto the first one's side of the shared edge
    const std::vector<Tri> folded = {welded[0], Tri{{{0, 0, 1}, {0, 0, 0}, {-0.5f, 0, 0.5f}}}};
    open = open_edges(blocks_of(folded), 2);
    EXPECT_EQ(open[0], 1 | 2 | 4);
    EXPECT_EQ(open[1], 1 | 2 | 4);
    // a fin standing on the shared edge: three triangles there
    std::vector<Tri> fin = welded;
    fin.push_back(Tri{{{0, 0, 0}, {0, 0, 1}, {0, 1, 0.5f}}});
    open = open_edges(blocks_of(fin), 3);
    EXPECT_EQ(open[0], 1 | 2 | 4);
    EXPECT_EQ(open[1], 1 | 2 | 4);
    EXPECT_EQ(open[2] & 1, 1);
    // a T-junction: the right side is split at (0,0,0.5), so no edge of the left one is matched
    const std::vector<Tri> t_junction = {welded[0], Tri{{{0, 0, 0}, {1, 0, 0}, {0, 0, 0.5f}}},
                                         Tri{{{0, 0, 0.5f}, {1, 0, 0}, {0, 0, 1}}}};
    open = open_edges(blocks_of(t_junction), 3);
    EXPECT_EQ(open[0], 1 | 2 | 4);
}

// Ten triangles fill two blocks, the second padded with repeats of the last triangle: a strip of
// ten, closed between neighbours and open on its outer sides and ends.
TEST(OpenEdges, AStripAcrossBlocks) {
    std::vector<Tri> strip;
    for (int i = 0; i < 5; ++i) {
        const float x0 = float(i), x1 = float(i + 1);
        strip.push_back(Tri{{{x0, 0, 0}, {x1, 0, 0}, {x1, 1, 0}}});
        strip.push_back(Tri{{{x0, 0, 0}, {x1, 1, 0}, {x0, 1, 0}}});
    }
    const std::vector<uint8_t> open = open_edges(blocks_of(strip), strip.size());
    int open_count = 0;
    for (uint8_t o : open) open_count += (o & 1) + ((o >> 1) & 1) + ((o >> 2) & 1);
    EXPECT_EQ(open_count, 12) << "5 + 5 long sides and the two ends";
    EXPECT_EQ(open[0], 1) << "its bottom side only";
    EXPECT_EQ(open[8], 1 | 2) << "its bottom side and the strip's end";
    EXPECT_EQ(open[9], 2) << "its top side only";
}
