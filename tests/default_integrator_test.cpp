// The integrator a scene gets without --integrator (integrators/default_integrator.h): SPPM where
// glass or smooth metal casts caustics of the scene's own lights (photons find them; the path
// tracer misses those of point lights altogether), the path tracer everywhere else: a diffuse or
// glossy scene under its own lights, or a scene lit only by its environment; SPPM (so that the
// error is plain: "no lights") when there is no light at all.
#include <gtest/gtest.h>

#include "integrators/default_integrator.h"
#include "scene/environment.h"
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
    const IntegratorChoice c = default_integrator(s);
    EXPECT_EQ(c.integrator, "pt");
    EXPECT_NE(c.reason.find("no glass or smooth metal"), std::string::npos) << c.reason;
    EnvironmentSettings env;
    env.has_color = true;
    env.color = {1.f, 1.f, 1.f};
    apply_environment(s, env, nullptr);
    EXPECT_EQ(default_integrator(s).integrator, "pt");                         // lamp and sky alike
    EXPECT_EQ(default_integrator(plane_of(MAT_METAL, 0.5f)).integrator, "pt"); // rough metal: no caustic to speak of
}

TEST(DefaultIntegrator, GlassOrSmoothMetalGetsPhotonMapping) {
    for (const Scene& s : {plane_of(MAT_GLASS), plane_of(MAT_MIRROR), plane_of(MAT_METAL, 0.1f)}) {
        const IntegratorChoice c = default_integrator(s);
        EXPECT_EQ(c.integrator, "sppm");
        EXPECT_NE(c.reason.find("casts caustics"), std::string::npos) << c.reason;
    }
    // An unused glass material casts nothing.
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    add_material(s, 1.f, 1.f, 1.f, 0.f, false, MAT_GLASS);
    EXPECT_EQ(default_integrator(s).integrator, "pt");
}

TEST(DefaultIntegrator, AnEnvironmentAloneGetsThePathTracer) {
    Scene s = plane_of(MAT_GLASS); // glass under the sky: the path tracer still, as measured
    s.punctual_lights.clear();
    apply_environment(s, EnvironmentSettings{}, nullptr); // the default white world
    ASSERT_TRUE(s.environment.present);
    const IntegratorChoice c = default_integrator(s);
    EXPECT_EQ(c.integrator, "pt");
    EXPECT_NE(c.reason.find("lit only by its environment"), std::string::npos);
}

TEST(DefaultIntegrator, NoLightAtAllStaysWithPhotonMapping) {
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    s.punctual_lights.clear();
    EnvironmentSettings off;
    off.default_light = false;
    apply_environment(s, off, nullptr);
    EXPECT_EQ(default_integrator(s).integrator, "sppm");
}
