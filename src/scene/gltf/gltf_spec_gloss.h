// KHR_materials_pbrSpecularGlossiness (archived) converted to the metallic-roughness model with
// KHR_materials_specular and KHR_materials_ior, as the archived extension's readme and
// glTF-Transform's metalRough() describe: base colour = diffuse; metallic 0; roughness =
// 1 - glossiness; the dielectric's F0 = the specular colour (an IOR of 1000, whose F0 of 0.996
// the specular colour factor divides out) and F90 = 1, Schlick's Fresnel in both models. A
// specularGlossinessTexture is read twice: its RGB as the specular colour texture (sRGB), its
// alpha, times glossinessFactor, baked into a new roughness texture (G = 1 - glossiness).
// What differs: spec-gloss weighs its diffuse by 1 - max(specular); the specular layer here
// weighs the base by its albedo (the same at normal incidence, energy-conserving elsewhere).
#pragma once
#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// Rewrites every material with the extension in `model`; returns how many.
int convert_specular_glossiness(tinygltf::Model& model, LoadContext& ctx);

} // namespace clppm::gltf
