// Which of a scene's materials some triangle uses: only those count where a scene's materials
// decide something (its lights, its kernels' features, its media, the default integrator).
#pragma once
#include <vector>

#include "scene/scene.h"

namespace clppm {

// used[i]: some triangle of `scene` has material i.
std::vector<bool> used_materials(const Scene& scene);

} // namespace clppm
