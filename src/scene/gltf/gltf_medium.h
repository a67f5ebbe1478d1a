// The world's medium a glTF file sets for itself: the default scene's (else the file's first
// scene's) extras.clppm_medium, {"density": D or [r, g, b], "albedo": a or [r, g, b],
// "anisotropy": g}, read into Scene::file_medium (docs/scenes.md, "Media").
#pragma once
#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

void read_file_medium(const tinygltf::Model& model, LoadContext& ctx, Scene& scene);

} // namespace clppm::gltf
