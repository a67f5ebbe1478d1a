// KHR_materials_variants: the file's named material variants. The default (no variant asked)
// keeps each primitive's own material; a variant gives each primitive the material its mappings
// name for it, where one does, as the extension's specification says.
#pragma once
#include <string>

#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// Records the variants' names in scene.variants and, for a non-empty `variant`, sets the
// primitives' materials in `model` to that variant's; an unknown name fails listing the names.
void apply_material_variant(tinygltf::Model& model, const std::string& variant, LoadContext& ctx, Scene& scene);

} // namespace clppm::gltf
