// The pose a glTF viewer shows a file in when it opens it: the nodes at the start of the file's
// first animation (glTF 2.0 Sec. 3.11), as the Khronos sample viewer plays it from its start and
// Blender's importer leaves it on its first frame.
#pragma once
#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// Sets each node that the first animation moves to its first keyframe's translation, rotation and
// scale (the value at the animation's start, since no channel starts before it). Morph target
// weights are not animated. A malformed channel fails the load with a one-line error naming it.
// Returns the number of channels applied.
int apply_animation_start(tinygltf::Model& model, LoadContext& ctx);

} // namespace clppm::gltf
