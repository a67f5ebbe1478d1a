// How much of what the camera sees the scene's own lights reach directly: a pilot of the default
// integrator (integrators/default_integrator.h) for scenes where no material decides. Where light
// samples from the first surfaces the camera sees are mostly blocked (a room lit through a doorway
// or a skylight), the light arrives by bounces that photons find and the path tracer finds only by
// chance (bench/RESULTS.md, "Light through a gap").
#pragma once
#include <cstdint>

#include "integrators/render_settings.h"
#include "scene/scene.h"

namespace clppm {

struct LightReach {
    bool measured = false; // false: the scene has no camera, no own lights, or too many triangles
    uint32_t hits = 0;     // camera rays of the pilot that met a surface
    double lit = 0;        // the fraction of light samples at those surfaces that reach their light
};

// Camera rays through an 8 x 8 grid of the image, and at each first surface 4 light samples
// (lights picked by power, points uniform on emissive triangles), traced on the host against every
// triangle (at most kLightReachMaxTriangles of them); deterministic.
LightReach light_reach(const Scene& scene, const RenderSettings& settings);

constexpr uint64_t kLightReachMaxTriangles = 300000;

} // namespace clppm
