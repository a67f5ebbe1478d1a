// Which kernel features a scene needs (kernels/kernel_features.h): the program is built with -DHAS_X=0
// for the rest, so scenes pay only for what they use. A few coarse flags only (LuxCore removed its
// fine-grained ones when users waited minutes for recompiles); programs are cached per option set.
#pragma once
#include <string>

#include "render_scene.h"
#include "scene.h"

namespace clppm {

struct SceneFeatures {
    bool mirror = false, glossy = false, dielectric = false, metal_mix = false, textures = false;
    bool area_lights = false, point_lights = false, spot_lights = false, directional_lights = false;
    bool thin_lens = false;
};

SceneFeatures scene_features(const Scene& scene, const DeviceScene& ds);

// "-DHAS_MIRROR=0 ..." for every absent feature; "" for the generic program.
std::string feature_build_options(const SceneFeatures& f);

// A short human-readable list: "diffuse, dielectric, area lights".
std::string describe_features(const SceneFeatures& f);

} // namespace clppm
