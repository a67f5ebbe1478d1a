// Parsing a glTF or GLB file with tinygltf after the pre-scan, behind the guarded file-system
// callbacks, with images decoded to 8-bit RGBA within the texel budget.
#pragma once
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// `base` is the scene's directory (empty: no external files); errors go through ctx.
tinygltf::Model parse_model(const std::vector<unsigned char>& bytes, const std::string& base, LoadContext& ctx);

} // namespace clppm::gltf
