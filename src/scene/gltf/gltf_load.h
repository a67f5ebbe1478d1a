// glTF 2.0 scene loading: .gltf (external or data-URI buffers) and .glb files become a Scene of
// world-space triangles, materials, textures, punctual lights and cameras.
//
// Material kind (dev::Material::kind) from the glTF parameters, in this order:
//   transmission > 0  -> MATERIAL_DIELECTRIC (KHR_materials_transmission; ior from KHR_materials_ior,
//                        default 1.5; roughness is ignored for now)
//   metallic >= 1     -> MATERIAL_MIRROR when roughness is 0 (tinted by base colour), else
//                        MATERIAL_GLOSSY (GGX conductor, alpha = roughness^2, F0 = base colour)
//   metallic > 0      -> MATERIAL_METAL_MIX (that metal with probability metallic, else diffuse)
//   otherwise         -> MATERIAL_DIFFUSE
// A primitive without a material gets the glTF specification's default material: base colour 1,
// metallic 1, roughness 1, which the mapping above makes a rough white MATERIAL_GLOSSY.
// emission = emissiveFactor * KHR_materials_emissive_strength.emissiveStrength.
//
// Every failure throws clppm::Error with one line that starts with the file path (or display name).
#pragma once
#include <string>

#include "scene/scene.h"

namespace clppm {

// Loads a .gltf or .glb file (detected by the GLB magic, not the extension). External files may
// only be referenced inside the file's directory.
Scene load_gltf(const std::string& path);

// Loads glTF JSON text held in memory. base_dir resolves external URIs; empty base_dir allows
// data: URIs only. display_name starts every error message and becomes Scene::source.
Scene load_gltf_text(const std::string& json_text, const std::string& base_dir, const std::string& display_name);

// The Cornell box compiled into the binary (scenes/cornell_box.gltf).
Scene load_default_scene();

} // namespace clppm
