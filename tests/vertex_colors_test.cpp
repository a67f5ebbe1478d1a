// COLOR_0 (glTF 2.0 Sec. 3.7.2.1): linear vertex colours multiply the base colour. Read from
// FLOAT and normalized integer accessors (white where a primitive has none), and a plate whose
// vertex colours multiply its base colour renders as the plate with the product as its factor.
#include <gtest/gtest.h>

#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

} // namespace

TEST(VertexColors, ReadPerCornerAndWhiteWhereAPrimitiveHasNone) {
    Scene s = load_gltf(data("vertex_colors.gltf"));
    ASSERT_EQ(s.num_triangles(), 2u);
    ASSERT_EQ(s.colors.size(), 6u);
    const std::array<float, 4> want[6] = {{1, 0, 0, 1}, {0, 1, 0, 128 / 255.f}, {0, 0, 0.2f, 0},
                                          {1, 1, 1, 1}, {1, 1, 1, 1},           {1, 1, 1, 1}};
    for (size_t i = 0; i < 6; ++i)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(s.colors[i][size_t(c)], want[i][size_t(c)], 1e-6) << i << " " << c;
    EXPECT_TRUE(load_gltf(data("texture.gltf")).colors.empty()) << "no COLOR_0, no colour buffer";
}

TEST(VertexColors, MultiplyTheBaseColour) {
    // The same material up to float rounding.
    expect_scenes_render_alike("color_plate_vertex.gltf", "color_plate_factor.gltf", 1e-3);
}
