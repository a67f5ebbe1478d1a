// Media that nest (src/scene/volume_nesting.h, kernels/medium.cl): which closed volume each surface
// and light lies in, found on the host, and what the integrators make of it:
// - the host's answer on a scene of cubes inside cubes, with a material used inside and outside;
// - two absorbing cubes, one inside the other, against Beer-Lambert's exp(-sigma_A l_A - sigma_B l_B)
//   along each pixel's ray (before nesting, the way from the outer cube's face to the inner's ran
//   in the world);
// - a fog cube mesh with a glowing block and its own light inside it renders as the same fog does
//   as the world's medium, by the path tracer and by SPPM (their light samples from the block and
//   from the fog cross the cube's medium, the path tracer samples lights inside it).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "medium_scenes.h"
#include "scene/device_scene.h"
#include "scene/gltf/gltf_load.h"
#include "scene/volume_nesting.h"
#include "scene_builders.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// An index-matched glass (ior 1) whose closed volume absorbs sigma, or scatters albedo of it.
uint32_t volume_material(Scene& s, std::array<float, 3> sigma, std::array<float, 3> albedo = {0, 0, 0}, float g = 0) {
    const uint32_t m = add_material(s, 1, 1, 1, 0, false, MAT_GLASS, 1.f, 0.f);
    dev::Material& v = s.materials[m];
    v.flags |= MATERIAL_FLAG_ENCLOSES_VOLUME;
    for (int k = 0; k < 3; ++k) v.attenuation[k] = sigma[size_t(k)], v.scatter[k] = albedo[size_t(k)];
    v.scatter[3] = g;
    return m;
}

// The first triangle of material m.
size_t first_of(const Scene& s, uint32_t m) {
    for (size_t t = 0; t < s.num_triangles(); ++t)
        if (s.shading[t].material == m) return t;
    return s.num_triangles();
}

} // namespace

TEST(VolumeNesting, EachSurfaceKnowsTheVolumeItLiesIn) {
    Scene s = glowing_box(0.5f, 1.f);
    const uint32_t walls = s.shading[0].material;
    const uint32_t outer = volume_material(s, {1, 1, 1}), inner = volume_material(s, {2, 2, 2});
    const uint32_t grey = add_material(s, 0.5f, 0.5f, 0.5f);
    add_box(s, {0, 0, -0.5f}, 0.4f, outer, false);
    add_box(s, {0, 0, -0.5f}, 0.2f, inner, false);
    const size_t in_inner = s.num_triangles();
    add_box(s, {0, 0, -0.5f}, 0.05f, grey, false); // inside both
    const size_t in_outer = s.num_triangles();
    add_box(s, {0.3f, 0.3f, -0.5f}, 0.05f, grey, false); // inside the outer cube only
    const size_t in_world = s.num_triangles();
    add_box(s, {0.7f, 0.7f, 0.5f}, 0.05f, grey, false); // outside both
    add_point_light(s, {0.f, 0.1f, -0.5f}, 1.f);        // inside the inner cube
    const size_t materials = s.materials.size();
    s.material_names.assign(materials, "");
    s.material_names[grey] = "grey";

    const Enclosures e = enclosures(s);
    EXPECT_EQ(e.triangles[first_of(s, walls)], kNoEnclosure);
    EXPECT_EQ(e.triangles[first_of(s, outer)], kNoEnclosure);
    EXPECT_EQ(s.shading[e.triangles[first_of(s, inner)]].material, outer);
    EXPECT_EQ(s.shading[e.triangles[in_inner]].material, inner);
    EXPECT_EQ(s.shading[e.triangles[in_outer]].material, outer);
    EXPECT_EQ(e.triangles[in_world], kNoEnclosure);
    ASSERT_EQ(e.lights.size(), 1u);
    EXPECT_EQ(s.shading[e.lights[0]].material, inner);

    nest_volumes(s);
    // grey lies in three volumes: its first stays, two copies with its name follow.
    ASSERT_EQ(s.materials.size(), materials + 2);
    EXPECT_EQ(s.material_names.size(), materials + 2);
    EXPECT_EQ(s.material_names.back(), "grey");
    EXPECT_EQ(s.materials[walls].outside, 0u);
    EXPECT_EQ(s.materials[outer].outside, 0u);
    EXPECT_EQ(s.materials[inner].outside, outer + 1);
    auto outside_of = [&](size_t t) { return s.materials[s.shading[t].material].outside; };
    EXPECT_EQ(outside_of(in_inner), inner + 1);
    EXPECT_EQ(outside_of(in_outer), outer + 1);
    EXPECT_EQ(outside_of(in_world), 0u);
    for (size_t t = in_inner; t < in_world + 12; ++t) EXPECT_EQ(s.materials[s.shading[t].material].base_color[0], 0.5f);
    EXPECT_TRUE(s.materials[inner].flags & MATERIAL_FLAG_HOLDS_LIGHTS);
    EXPECT_FALSE(s.materials[outer].flags & MATERIAL_FLAG_HOLDS_LIGHTS);
}

TEST(VolumeNesting, AScenesWithoutNestingIsLeftAlone) {
    Scene s = scattering_cube(0.5f, {0.5f, 1.f, 2.f}, {1.f, 1.f, 1.f}, 0.4f);
    const std::vector<dev::TriShading> shading = s.shading;
    const size_t materials = s.materials.size();
    nest_volumes(s);
    EXPECT_EQ(s.materials.size(), materials);
    for (size_t t = 0; t < s.num_triangles(); ++t) EXPECT_EQ(s.shading[t].material, shading[t].material);
    for (const dev::Material& m : s.materials) {
        EXPECT_EQ(m.outside, 0u);
        EXPECT_FALSE(m.flags & MATERIAL_FLAG_HOLDS_LIGHTS);
    }
}

// Two absorbing index-matched cubes, one inside the other, between the camera and the glowing
// black walls: exp(-sigma_A (l_A - l_B) - sigma_B l_B), l the lengths of the ray inside each.
TEST(VolumeNesting, AnAbsorberInsideAnAbsorberIsBeerLambert) {
    const std::array<float, 3> sa{0.8f, 1.5f, 0.3f}, sb{2.f, 0.2f, 1.f};
    const D3 centre{0, 0, -0.5};
    Scene scene = glowing_box(0.f, 1.f);
    add_box(scene, {0, 0, -0.5f}, 0.45f, volume_material(scene, sa), false);
    add_box(scene, {0, 0, -0.5f}, 0.2f, volume_material(scene, sb), false);
    for (const char* integrator : {"pt", "sppm"}) {
        SCOPED_TRACE(integrator);
        RenderSettings s = pt_settings(24);
        s.integrator = integrator;
        const Image img = render_passes(scene, s, 64);
        expect_clean(img);
        const dev::Camera cam = camera_of(scene, s);
        for (int c = 0; c < 3; ++c) {
            auto ref = [&](D3 d) {
                double a_in, a_out, b_in, b_out;
                slab({0, 0, 0}, d, centre, 0.45, &a_in, &a_out);
                slab({0, 0, 0}, d, centre, 0.2, &b_in, &b_out);
                const double la = a_out > a_in ? a_out - a_in : 0.0, lb = b_out > b_in ? b_out - b_in : 0.0;
                return std::exp(-sa[size_t(c)] * (la - lb) - sb[size_t(c)] * lb);
            };
            expect_region(img, cam, 0, 24, c, 0.01, ref, "the whole image");
            expect_region(img, cam, 9, 15, c, 0.01, ref, "through the inner cube");
        }
    }
}

// The glowing box's fog as the world's medium, and as the medium of an index-matched cube just
// inside the walls, with a glowing grey block and a point light in the fog: the same light either
// way. The block's faces and the light lie inside the cube, so segments that end on the block ran
// in the cube's fog, light samples from the block cross it, and the path tracer's scattering
// points inside the cube sample the block and the light (the cube holds lights).
TEST(VolumeNesting, ObjectsAndLightsInAFogCubeSeeTheFog) {
    const std::array<float, 3> sigma{0.6f, 1.f, 1.5f}, albedo{0.9f, 0.7f, 0.5f};
    const float g = 0.3f;
    auto furnish = [](Scene& s) {
        add_box(s, {0.1f, -0.2f, -0.5f}, 0.2f, add_material(s, 0.3f, 0.5f, 0.7f, 2.f), false);
        add_point_light(s, {-0.4f, 0.5f, -0.3f}, 0.5f);
    };
    Scene world = glowing_box(0.5f, 1.f);
    set_medium(world, sigma, albedo, g);
    furnish(world);
    Scene cube = scattering_cube(0.5f, sigma, albedo, g);
    furnish(cube);
    struct Case {
        const char* integrator;
        uint64_t passes;
        double tol;
    };
    for (const Case& k : {Case{"pt", 512, 0.03}, Case{"sppm", 128, 0.04}}) {
        SCOPED_TRACE(k.integrator);
        RenderSettings s = pt_settings(16, 1024);
        s.integrator = k.integrator;
        s.photons = 20000;
        const Image a = render_passes(world, s, k.passes), b = render_passes(cube, s, k.passes);
        expect_clean(b);
        for (int c = 0; c < 3; ++c) {
            const double wa = region_mean(a, 0, 0, 16, 16, c), wb = region_mean(b, 0, 0, 16, 16, c);
            EXPECT_NEAR(wb / wa, 1.0, k.tol) << "channel " << c << ": cube " << wb << ", world " << wa;
            const double ca = region_mean(a, 5, 7, 11, 13, c), cb = region_mean(b, 5, 7, 11, 13, c);
            EXPECT_NEAR(cb / ca, 1.0, k.tol) << "channel " << c << ", the block: cube " << cb << ", world " << ca;
        }
    }
}

// The same from files (tests/data/make_test_gltf.py): fog_cube_room.gltf holds fog_room.gltf's
// room, glass cube and lights in a fog cube mesh (KHR_materials_volume_scatter) in place of the
// world's medium; with the world's single-scattering albedo set to the one the mesh's
// multiscatterColor inverts to, both render the same light (measured: sppm 0.99970, pt 0.99978 at
// 48 x 48 and 64 passes).
TEST(VolumeNesting, AFogCubeMeshRendersAsTheWorldsFog) {
    Scene world = load_gltf(std::string(CLPPM_TEST_DATA) + "/fog_room.gltf");
    const Scene cube = load_gltf(std::string(CLPPM_TEST_DATA) + "/fog_cube_room.gltf");
    std::array<float, 3> albedo{};
    const float ms[3] = {0.9f, 0.8f, 0.7f};
    for (int c = 0; c < 3; ++c) {
        const double m = ms[c], s = 4.09712 + 4.20863 * m - std::sqrt(9.59217 + 41.6808 * m + 17.7126 * m * m);
        albedo[size_t(c)] = float(1 - s * s);
    }
    set_medium(world, {0.3f, 0.4f, 0.6f}, albedo, 0.4f);
    ASSERT_FALSE(cube.has_file_medium);
    for (const char* integrator : {"pt", "sppm"}) {
        SCOPED_TRACE(integrator);
        RenderSettings s = pt_settings(32);
        s.integrator = integrator;
        s.photons = 20000;
        const Image a = render_passes(world, s, 32), b = render_passes(cube, s, 32);
        expect_clean(b);
        for (int c = 0; c < 3; ++c) {
            const double wa = region_mean(a, 0, 0, 32, 32, c), wb = region_mean(b, 0, 0, 32, 32, c);
            EXPECT_NEAR(wb / wa, 1.0, 0.01) << "channel " << c << ": cube " << wb << ", world " << wa;
        }
    }
}
