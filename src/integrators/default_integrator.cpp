#include "integrators/default_integrator.h"

#include <cstdio>
#include <vector>

#include "integrators/light_reach.h"
#include "scene/environment.h"
#include "scene/medium.h"
#include "scene/used_materials.h"

namespace clppm {

namespace {

// Glass of any roughness (shadow rays do not pass it: light behind it reaches the path tracer
// only by chance) and metal smoother than this (its narrow lobe makes the path tracer's light
// samples spiky; below 0.01 the lobe is a delta it cannot sample at all) cast caustics.
constexpr float kCausticRoughness = 0.2f;

// The name (or index) of a material some triangle uses that casts caustics; "" when none does.
std::string caustic_material(const Scene& scene) {
    const std::vector<bool> used = used_materials(scene);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const dev::Material& m = scene.materials[i];
        if (used[i] && (m.transmission > 0.f || (m.metallic > 0.f && m.roughness < kCausticRoughness)))
            return i < scene.material_names.size() && !scene.material_names[i].empty() ? scene.material_names[i]
                                                                                       : "#" + std::to_string(i);
    }
    return "";
}

// What keeps VCM from rendering this view, "" when nothing does: its light sub-paths reach the
// camera through a pinhole's or a thin lens's importance (kernels/vcm.cl), and they splat with the
// box filter only.
std::string vcm_obstacle(const Scene& scene, const RenderSettings& settings) {
    if (settings.camera < scene.cameras.size() && scene.cameras[settings.camera].orthographic)
        return "the camera is orthographic";
    if (settings.filter == PixelFilter::Tent) return "--filter tent";
    return "";
}

} // namespace

const char* const kDefaultIntegratorRule =
    "in participating media sppm where glass or smooth metal casts caustics from the scene's own lights (volumetric "
    "caustics), pt otherwise; without media vcm where they cast caustics (sppm for an orthographic camera or --filter "
    "tent), sppm where the lights reach under 5% of what the camera sees directly (light through a gap), pt "
    "otherwise; measured: bench/RESULTS.md";

IntegratorChoice default_integrator(const Scene& scene, const RenderSettings& settings, bool chains_allowed) {
    const bool own_lights = scene_has_lights(scene);
    if (!own_lights && !scene.environment.present) // no light at all: the error says so
        return {"sppm", "the scene has no lights"};
    const std::string caustic = own_lights ? caustic_material(scene) : "";
    if (scene_has_media(scene)) {
        const std::string medium = scene.medium.present
                                       ? "the world has a participating medium (" + scene.medium.source + ")"
                                       : "a mesh's volume scatters (KHR_materials_volume_scatter)";
        if (!caustic.empty())
            return {"sppm", medium + " and material " + caustic +
                                " (glass or smooth metal) focuses the scene's lights into it: volumetric caustics, "
                                "which photons find (--integrator pt for the path tracer)"};
        return {"pt", medium + ", where the path tracer converges fastest without caustics (--integrator sppm for "
                               "photon mapping)"};
    }
    if (!caustic.empty()) {
        // VCM had 20 to 40 times SPPM's box-4 error less on the caustic scenes, measured against
        // references that do not share SPPM's blur (bench/RESULTS.md, "SPPM, the default for
        // caustics, against references that do not share its bias").
        const std::string why = "material " + caustic + " (glass or smooth metal) casts caustics of the scene's lights";
        const std::string obstacle = vcm_obstacle(scene, settings);
        if (obstacle.empty())
            return {"vcm", why + ", which vertex connection and merging finds without photon mapping's blur "
                                 "(--integrator sppm for photon mapping, pt for the path tracer)"};
        return {"sppm", why + ", which photons find: stochastic progressive photon mapping (" + obstacle +
                            ", which vertex connection and merging cannot render; --integrator pt for the path "
                            "tracer)"};
    }
    if (!own_lights)
        return {"pt", "the scene is lit only by its environment, where the path tracer converges fastest "
                      "(--integrator sppm for photon mapping)"};
    const LightReach reach = light_reach(scene, settings);
    char lit[64];
    std::snprintf(lit, sizeof lit, "%.0f%%", 100.0 * reach.lit);
    if (reach.measured && reach.lit < kGapReach) {
        // Directional lights send their photons over the scene's whole bounding disc: through a
        // gap, most land where nothing is seen, and the chains keep the few that are.
        bool distant = false;
        for (const dev::Light& l : scene.punctual_lights) distant = distant || l.type == LIGHT_DIRECTIONAL;
        IntegratorChoice c{"sppm",
                           std::string("the lights reach only ") + lit +
                               " of what the camera sees directly (light through a gap), where photons find the "
                               "light that bounces in: stochastic progressive photon mapping"};
        if (distant && chains_allowed) {
            c.visual_importance = true;
            c.reason += ", with visual importance for the directional light's photons";
        }
        c.reason += " (--integrator pt for the path tracer)";
        return c;
    }
    return {"pt", std::string("no glass or smooth metal casts caustics here, where the path tracer converges fastest") +
                      (reach.measured ? std::string(" (the lights reach ") + lit + " of what the camera sees)" : "") +
                      " (--integrator sppm for photon mapping)"};
}

} // namespace clppm
