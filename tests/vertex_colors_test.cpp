// COLOR_0 (glTF 2.0 Sec. 3.7.2.1): linear vertex colours multiply the base colour. Read from
// FLOAT and normalized integer accessors (white where a primitive has none), and a plate whose
// vertex colours multiply its base colour renders as the plate with the product as its factor.
#include <gtest/gtest.h>

#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

std::string data(const char* name) { return std::string(CLPPM_TEST_DATA) + "/" + name; }

double render_mean(const char* file, const char* integrator) {
    std::string d = make_temp_dir("vcolor"), out;
    const std::string args = data(file) + " --width 48 --height 32 --passes 6 --photons 50000 --quiet --no-png" +
                             " --integrator " + integrator + " -o " + d + "/i.exr";
    EXPECT_EQ(run_clppm(args, &out), 0) << out;
    return mean_radiance(read_exr(d + "/i.exr"));
}

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
    for (const char* integrator : {"sppm", "pt"}) {
        SCOPED_TRACE(integrator);
        const double vertex = render_mean("color_plate_vertex.gltf", integrator);
        const double factor = render_mean("color_plate_factor.gltf", integrator);
        ASSERT_GT(factor, 0);
        EXPECT_NEAR(vertex / factor, 1.0, 1e-3); // the same material up to float rounding
    }
}
