// The integrator a scene gets without --integrator (integrators/default_integrator.h): VCM where
// glass or smooth metal casts caustics of the scene's own lights (its merges find them; the path
// tracer misses those of point lights altogether), SPPM there when VCM cannot render the view (an
// orthographic camera, --filter tent), the path tracer everywhere else: a diffuse or
// glossy scene under its own lights, or a scene lit only by its environment; SPPM (so that the
// error is plain: "no lights") when there is no light at all; SPPM, with visual importance for a
// directional light, where the lights reach almost nothing the camera sees (light through a gap).
// In participating media: SPPM where glass or smooth metal focuses the lights into them
// (volumetric caustics), the path tracer otherwise.
#include <gtest/gtest.h>

#include "integrators/default_integrator.h"
#include "integrators/light_reach.h"
#include "scene/environment.h"
#include "scene/gltf/gltf_load.h"
#include "scene_builders.h"

using namespace clppm;
using namespace clppm::test;

namespace {

// The plane of plane_under_point_light in another material.
Scene plane_of(TestMaterial kind, float roughness = 1.f) {
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    s.materials[0] = s.materials[size_t(add_material(s, 0.8f, 0.8f, 0.8f, 0.f, false, kind, 1.5f, roughness))];
    return s;
}

} // namespace

TEST(DefaultIntegrator, ADiffuseSceneUnderItsOwnLightsGetsThePathTracer) {
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    const IntegratorChoice c = default_integrator(s, RenderSettings{}, true);
    EXPECT_EQ(c.integrator, "pt");
    EXPECT_NE(c.reason.find("no glass or smooth metal"), std::string::npos) << c.reason;
    EnvironmentSettings env;
    env.has_color = true;
    env.color = {1.f, 1.f, 1.f};
    apply_environment(s, env, nullptr);
    EXPECT_EQ(default_integrator(s, RenderSettings{}, true).integrator, "pt"); // lamp and sky alike
    EXPECT_EQ(default_integrator(plane_of(MAT_METAL, 0.5f), RenderSettings{}, true).integrator,
              "pt"); // rough metal: no caustic to speak of
}

TEST(DefaultIntegrator, MediaGetPhotonsForVolumetricCausticsAndThePathTracerOtherwise) {
    auto fog = [](Scene s) {
        s.medium.present = true;
        s.medium.medium = MediumDesc{{0.3f, 0.3f, 0.3f}, {0.9f, 0.9f, 0.9f}, 0.f};
        s.medium.source = "<test>";
        return s;
    };
    IntegratorChoice c = default_integrator(fog(plane_of(MAT_GLASS)), RenderSettings{}, true);
    EXPECT_EQ(c.integrator, "sppm");
    EXPECT_NE(c.reason.find("volumetric caustics"), std::string::npos) << c.reason;
    c = default_integrator(fog(plane_under_point_light(0.5f, 10.f, 1.f)), RenderSettings{}, true);
    EXPECT_EQ(c.integrator, "pt");
    EXPECT_NE(c.reason.find("participating medium"), std::string::npos) << c.reason;
}

TEST(DefaultIntegrator, GlassOrSmoothMetalGetsVertexConnectionAndMerging) {
    for (const Scene& s : {plane_of(MAT_GLASS), plane_of(MAT_MIRROR), plane_of(MAT_METAL, 0.1f)}) {
        const IntegratorChoice c = default_integrator(s, RenderSettings{}, true);
        EXPECT_EQ(c.integrator, "vcm");
        EXPECT_NE(c.reason.find("casts caustics"), std::string::npos) << c.reason;
    }
    // Where VCM cannot render the view, photon mapping, and the note says why.
    Scene ortho = plane_of(MAT_GLASS);
    ASSERT_FALSE(ortho.cameras.empty());
    ortho.cameras[0].orthographic = true;
    IntegratorChoice c = default_integrator(ortho, RenderSettings{}, true);
    EXPECT_EQ(c.integrator, "sppm");
    EXPECT_NE(c.reason.find("the camera is orthographic"), std::string::npos) << c.reason;
    RenderSettings tent;
    tent.filter = PixelFilter::Tent;
    c = default_integrator(plane_of(MAT_GLASS), tent, true);
    EXPECT_EQ(c.integrator, "sppm");
    EXPECT_NE(c.reason.find("--filter tent"), std::string::npos) << c.reason;
    // An unused glass material casts nothing.
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    add_material(s, 1.f, 1.f, 1.f, 0.f, false, MAT_GLASS);
    EXPECT_EQ(default_integrator(s, RenderSettings{}, true).integrator, "pt");
}

TEST(DefaultIntegrator, AnEnvironmentAloneGetsThePathTracer) {
    Scene s = plane_of(MAT_GLASS); // glass under the sky: the path tracer still, as measured
    s.punctual_lights.clear();
    apply_environment(s, EnvironmentSettings{}, nullptr); // the default white world
    ASSERT_TRUE(s.environment.present);
    const IntegratorChoice c = default_integrator(s, RenderSettings{}, true);
    EXPECT_EQ(c.integrator, "pt");
    EXPECT_NE(c.reason.find("lit only by its environment"), std::string::npos);
}

TEST(DefaultIntegrator, NoLightAtAllStaysWithPhotonMapping) {
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    s.punctual_lights.clear();
    EnvironmentSettings off;
    off.default_light = false;
    apply_environment(s, off, nullptr);
    EXPECT_EQ(default_integrator(s, RenderSettings{}, true).integrator, "sppm");
}

// The pilot (integrators/light_reach.h): what fraction of light samples from the surfaces the
// camera sees reach their light. The diffuse Cornell box's lamp reaches most of the box, the doorway's
// a quarter (room B's floor through the door), the skylit room's sun almost nothing (its patch
// on the floor is at the image's edge).
TEST(DefaultIntegrator, LightReachOfThreeRooms) {
    const LightReach box = light_reach(load_gltf(CLPPM_SCENES_DIR "/cornell_box.gltf"), RenderSettings{});
    const LightReach door = light_reach(load_gltf(CLPPM_SCENES_DIR "/doorway.gltf"), RenderSettings{});
    const LightReach sky = light_reach(load_gltf(CLPPM_SCENES_DIR "/skylight.gltf"), RenderSettings{});
    ASSERT_TRUE(box.measured && door.measured && sky.measured);
    EXPECT_EQ(sky.hits, 64u); // a closed room: every pilot ray meets a wall
    EXPECT_GT(box.lit, 0.6);
    EXPECT_GT(door.lit, 0.12);
    EXPECT_LT(door.lit, 0.4);
    EXPECT_LT(sky.lit, 0.03);
    // No camera: nothing to measure, and the rule falls back on the path tracer.
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    s.cameras.clear();
    EXPECT_FALSE(light_reach(s, RenderSettings{}).measured);
}

// Light through a gap: the skylit room gets SPPM, with visual importance for its sun's photons
// unless the render cannot have it (several devices or processes, an error estimate); the
// doorway, whose lamp reaches a quarter of the view, keeps the path tracer (measured best there).
TEST(DefaultIntegrator, LightThroughAGapGetsPhotonMapping) {
    const Scene sky = load_gltf(CLPPM_SCENES_DIR "/skylight.gltf");
    IntegratorChoice c = default_integrator(sky, RenderSettings{}, true);
    EXPECT_EQ(c.integrator, "sppm");
    EXPECT_TRUE(c.visual_importance);
    EXPECT_NE(c.reason.find("light through a gap"), std::string::npos) << c.reason;
    c = default_integrator(sky, RenderSettings{}, false);
    EXPECT_EQ(c.integrator, "sppm");
    EXPECT_FALSE(c.visual_importance);
    c = default_integrator(load_gltf(CLPPM_SCENES_DIR "/doorway.gltf"), RenderSettings{}, true);
    EXPECT_EQ(c.integrator, "pt");
    EXPECT_FALSE(c.visual_importance);
}
