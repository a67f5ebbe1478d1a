// Kernels specialised for a scene's features give the same image as the generic kernels, bit for
// bit with the same seed, on every shipped scene; and the specialisation really removes features.
#include <gtest/gtest.h>

#include "io/image_io.h"
#include "scene/gltf/gltf_load.h"
#include "scene/scene_features.h"
#include "test_util.h"

using namespace clppm;
using namespace clppm::test;

TEST(Specialization, SameImageAsGenericKernelsOnEveryShippedScene) {
    const std::string scenes = CLPPM_SCENES_DIR;
    for (const std::string& scene : {std::string(), scenes + "/caustic.gltf", scenes + "/furnace.gltf",
                                     scenes + "/plane_point_light.gltf", scenes + "/bunny_100k.gltf"}) {
        // SPPM shares every kernel that specialisation touches with PPM; one scene checks it too.
        for (const char* integrator : {"ppm", "sppm"}) {
            if (std::string(integrator) == "sppm" && !scene.empty()) continue;
            std::string d = make_temp_dir("spec"), out;
            const std::string args = scene + " --width 32 --height 24 --passes 3 --photons 20000 --quiet --no-png" +
                                     " --integrator " + integrator;
            ASSERT_EQ(run_clppm(args + " -o " + d + "/s.exr --stats-json " + d + "/s.json", &out), 0) << out;
            ASSERT_EQ(run_clppm(args + " -o " + d + "/g.exr --generic-kernels", &out), 0) << out;
            Image s = read_exr(d + "/s.exr"), g = read_exr(d + "/g.exr");
            EXPECT_EQ(s.rgb, g.rgb) << (scene.empty() ? "default scene" : scene) << ", " << integrator;
            EXPECT_GT(mean_radiance(s), 0.0) << scene;
        }
    }
}

// The material and geometry features' test scenes, where a texture can bring back a lobe the
// factors alone leave out (a transmissionTexture gives the dielectric base its specular layer).
TEST(Specialization, SameImageAsGenericKernelsOnTheFeatureScenes) {
    for (const char* file :
         {"transmission_texture.gltf", "mr_texture.gltf",       "alpha_mask_card.gltf",    "alpha_blend_blend.gltf",
          "normal_plate_mapped.gltf",  "emissive_texture.gltf", "color_plate_vertex.gltf", "uv1_plate_set1.gltf",
          "volume_slab.gltf",          "specular_texture.gltf", "ref_rough_glass.gltf",    "env_outdoor.gltf",
          "unlit_panel.gltf",          "coat_textured.gltf",    "coat_rough_plate.gltf",   "sheen_textured.gltf",
          "film_textured.gltf",        "film_plate.gltf",       "ortho_square.gltf",       "znear_clipped.gltf",
          "aniso_plate.gltf",          "dt_textured.gltf",      "dt_box_volume.gltf",      "prism.gltf",
          "prism_plain.gltf"}) {
        std::string d = make_temp_dir("spec_features"), out;
        const std::string args = std::string(CLPPM_TEST_DATA) + "/" + file +
                                 " --width 32 --height 24 --passes 2 --photons 20000 --quiet --no-png --integrator ppm";
        ASSERT_EQ(run_clppm(args + " -o " + d + "/s.exr", &out), 0) << out;
        ASSERT_EQ(run_clppm(args + " -o " + d + "/g.exr --generic-kernels", &out), 0) << out;
        EXPECT_EQ(read_exr(d + "/s.exr").rgb, read_exr(d + "/g.exr").rgb) << file;
    }
}

// The media scenes (the world's fog, a scattering mesh), which the path tracer alone renders.
TEST(Specialization, SameImageAsGenericKernelsInMedia) {
    for (const char* file : {"fog_room.gltf", "wax_block.gltf"}) {
        std::string d = make_temp_dir("spec_media"), out;
        const std::string args = std::string(CLPPM_TEST_DATA) + "/" + file +
                                 " --width 32 --height 24 --passes 3 --quiet --no-png --integrator pt";
        ASSERT_EQ(run_clppm(args + " -o " + d + "/s.exr", &out), 0) << out;
        ASSERT_EQ(run_clppm(args + " -o " + d + "/g.exr --generic-kernels", &out), 0) << out;
        const Image s = read_exr(d + "/s.exr");
        EXPECT_EQ(s.rgb, read_exr(d + "/g.exr").rgb) << file;
        EXPECT_GT(mean_radiance(s), 0.0) << file;
    }
}

TEST(Specialization, BuildOptionsRemoveWhatTheSceneDoesNotUse) {
    Scene box = load_default_scene();
    Scene furnace = load_gltf(std::string(CLPPM_SCENES_DIR) + "/furnace.gltf");
    DeviceScene ds; // only lights and camera are read
    dev::Light area{};
    area.type = LIGHT_TRIANGLE;
    ds.lights.push_back(area);
    SceneFeatures fb = scene_features(box, ds), ff = scene_features(furnace, ds);
    // The box: Lambertian walls, a mirror sphere (metal) and a glass one; the glass has no
    // opaque part, so no specular layer either.
    EXPECT_TRUE(fb.metal && fb.glass && fb.area_lights);
    EXPECT_FALSE(fb.specular_layer || fb.rough_glass || fb.textures || fb.spot_lights || fb.point_lights ||
                 fb.thin_lens);
    EXPECT_EQ(
        feature_build_options(ff),
        "-DHAS_SPECULAR_LAYER=0 -DHAS_METAL=0 -DHAS_GLASS=0 -DHAS_ROUGH_GLASS=0 -DHAS_TEXTURES=0 -DHAS_NORMAL_MAPS=0 "
        "-DHAS_VERTEX_COLORS=0 -DHAS_ALPHA=0 -DHAS_VOLUME=0 -DHAS_POINT_LIGHTS=0 -DHAS_SPOT_LIGHTS=0 "
        "-DHAS_DIRECTIONAL_LIGHTS=0 -DHAS_ENV_LIGHT=0 -DHAS_THIN_LENS=0 -DHAS_EMISSION_SPREAD=0 -DHAS_UNLIT=0 "
        "-DHAS_CLEARCOAT=0 -DHAS_SHEEN=0 -DHAS_ORTHOGRAPHIC=0 -DHAS_IRIDESCENCE=0 -DHAS_ANISOTROPY=0 "
        "-DHAS_DIFFUSE_TRANSMISSION=0 -DHAS_DISPERSION=0 -DHAS_MEDIUM=0");
    EXPECT_EQ(feature_build_options(SceneFeatures::all()), "");
}
