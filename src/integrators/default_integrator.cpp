#include "integrators/default_integrator.h"

#include <vector>

#include "scene/environment.h"

namespace clppm {

namespace {

// Glass of any roughness (shadow rays do not pass it: light behind it reaches the path tracer
// only by chance) and metal smoother than this (its narrow lobe makes the path tracer's light
// samples spiky; below 0.01 the lobe is a delta it cannot sample at all) cast caustics.
constexpr float kCausticRoughness = 0.2f;

// The name (or index) of a material some triangle uses that casts caustics; "" when none does.
std::string caustic_material(const Scene& scene) {
    std::vector<bool> used(scene.materials.size(), false);
    for (const dev::TriShading& t : scene.shading)
        if (t.material < used.size()) used[t.material] = true;
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const dev::Material& m = scene.materials[i];
        if (used[i] && (m.transmission > 0.f || (m.metallic > 0.f && m.roughness < kCausticRoughness)))
            return i < scene.material_names.size() && !scene.material_names[i].empty() ? scene.material_names[i]
                                                                                       : "#" + std::to_string(i);
    }
    return "";
}

} // namespace

const char* const kDefaultIntegratorRule =
    "sppm where glass or smooth metal casts caustics from the scene's own lights, pt otherwise; measured: "
    "bench/RESULTS.md";

IntegratorChoice default_integrator(const Scene& scene) {
    const bool own_lights = scene_has_lights(scene);
    if (!own_lights && !scene.environment.present) // no light at all: the error says so
        return {"sppm", "the scene has no lights"};
    const std::string caustic = own_lights ? caustic_material(scene) : "";
    if (!caustic.empty())
        return {"sppm", "material " + caustic +
                            " (glass or smooth metal) casts caustics of the scene's lights, which photons find: "
                            "stochastic progressive photon mapping (--integrator pt for the path tracer)"};
    if (!own_lights)
        return {"pt", "the scene is lit only by its environment, where the path tracer converges fastest "
                      "(--integrator sppm for photon mapping)"};
    return {"pt", "no glass or smooth metal casts caustics here, where the path tracer converges fastest "
                  "(--integrator sppm for photon mapping)"};
}

} // namespace clppm
