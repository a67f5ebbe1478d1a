// glTF 2.0 scene loading: .gltf (external or data-URI buffers) and .glb files become a Scene of
// world-space triangles, materials, textures, punctual lights and cameras.
//
// Materials keep glTF's parameters (metallic, roughness, KHR_materials_transmission, _ior,
// _specular); kernels/bsdf.cl is the scattering model they define, and docs/scenes.md the mapping.
// A primitive without a material gets the glTF specification's default material: base colour 1,
// metallic 1, roughness 1 (a rough white metal).
// emission = emissiveFactor * KHR_materials_emissive_strength.emissiveStrength.
//
// Every failure throws clppm::Error with one line that starts with the file path (or display name).
#pragma once
#include <string>

#include "scene/scene.h"

namespace clppm {

// Loads a .gltf or .glb file (detected by the GLB magic, not the extension). External files may
// only be referenced inside the file's directory.
// `variant`: a KHR_materials_variants name to render (empty: the file's default materials).
Scene load_gltf(const std::string& path, const std::string& variant = "");

// Loads glTF JSON text held in memory. base_dir resolves external URIs; empty base_dir allows
// data: URIs only. display_name starts every error message and becomes Scene::source.
Scene load_gltf_text(const std::string& json_text, const std::string& base_dir, const std::string& display_name);

// The Cornell box compiled into the binary (scenes/cornell_box.gltf).
Scene load_default_scene();

} // namespace clppm
