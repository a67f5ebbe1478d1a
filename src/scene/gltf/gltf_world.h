// The world a glTF file sets for itself: the default scene's (else the file's first scene's)
// extras.clppm_environment, {"color": [r, g, b]} or {"image": URI, "strength": s, "rotation": deg},
// read into Scene::file_world. The image's URI is relative to the file and must stay inside its
// folder, as the file's other resources must.
#pragma once
#include <string>

#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// `base`: the file's folder (absolute), empty for a file without one (the built-in scene).
void read_file_world(const tinygltf::Model& model, const std::string& base, LoadContext& ctx, Scene& scene);

} // namespace clppm::gltf
