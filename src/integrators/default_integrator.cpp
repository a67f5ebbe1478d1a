#include "integrators/default_integrator.h"

#include "scene/environment.h"

namespace clppm {

const char* const kDefaultIntegratorRule =
    "sppm for a scene with lights of its own, pt for one lit only by an environment; measured: bench/RESULTS.md";

IntegratorChoice default_integrator(const Scene& scene) {
    if (!scene_has_lights(scene) && scene.environment.present)
        return {"pt", "the scene is lit only by its environment, where the path tracer converges fastest "
                      "(--integrator sppm for photon mapping)"};
    return {"sppm", "the scene has lights of its own: stochastic progressive photon mapping"};
}

} // namespace clppm
