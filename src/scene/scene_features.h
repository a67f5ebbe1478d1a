// Which kernel features a scene needs (kernels/kernel_features.h): the program is built with -DHAS_X=0
// for the rest, so scenes pay only for what they use. A few coarse flags only (LuxCore removed its
// fine-grained ones when users waited minutes for recompiles); programs are cached per option set.
#pragma once
#include <string>

#include "kernel_features.h"
#include "scene/device_scene.h"
#include "scene/scene.h"

namespace clppm {

// One bool per entry of CLPPM_KERNEL_FEATURES, in its order.
struct SceneFeatures {
#define CLPPM_FEATURE_FIELD(flag, field, text) bool field = false;
    CLPPM_KERNEL_FEATURES(CLPPM_FEATURE_FIELD)
#undef CLPPM_FEATURE_FIELD

    // Every feature: the generic program's.
    static SceneFeatures all();
};

SceneFeatures scene_features(const Scene& scene, const DeviceScene& ds);

// "-DHAS_METAL=0 ..." for every absent feature; "" for the generic program.
std::string feature_build_options(const SceneFeatures& f);

// A short human-readable list: "diffuse, dielectric, area lights".
std::string describe_features(const SceneFeatures& f);

} // namespace clppm
