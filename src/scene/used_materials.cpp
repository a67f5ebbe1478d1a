#include "scene/used_materials.h"

namespace clppm {

std::vector<bool> used_materials(const Scene& scene) {
    std::vector<bool> used(scene.materials.size(), false);
    for (const dev::TriShading& t : scene.shading)
        if (t.material < used.size()) used[t.material] = true;
    return used;
}

} // namespace clppm
