// The integrator a scene gets without --integrator (cli/default_integrator.h): SPPM with lights of
// its own, however an environment adds to them; the path tracer when the environment is its only
// light; SPPM (so that the error is plain: "no lights") when there is no light at all.
#include <gtest/gtest.h>

#include "integrators/default_integrator.h"
#include "scene/environment.h"
#include "scene_builders.h"

using namespace clppm;
using namespace clppm::test;

TEST(DefaultIntegrator, LightsOfItsOwnGetPhotonMapping) {
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
    EXPECT_EQ(default_integrator(s).integrator, "sppm");
    EnvironmentSettings env;
    env.has_color = true;
    env.color = {1.f, 1.f, 1.f};
    apply_environment(s, env, nullptr);
    ASSERT_TRUE(s.environment.present);
    EXPECT_EQ(default_integrator(s).integrator, "sppm"); // the lamp still casts what photons find
}

TEST(DefaultIntegrator, AnEnvironmentAloneGetsThePathTracer) {
    Scene s = plane_under_point_light(0.5f, 10.f, 1.f);
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
