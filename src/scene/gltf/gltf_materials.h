// glTF materials and their textures -> dev::Material and dev::Texture, as the README maps them:
// factors checked finite and clamped, the material kind from metallic, roughness and
// transmission, base colour textures decoded from sRGB.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

class MaterialConverter {
public:
    MaterialConverter(const tinygltf::Model& m, LoadContext& ctx, Scene& s) : m_(m), ctx_(ctx), s_(s) {}

    // Every material of the file, in its order: scene material i is glTF material i.
    void convert_materials();
    // The scene material of a primitive's glTF `material` (-1: glTF's default material, added once).
    uint32_t material_index(int gltf_material, const std::string& owner);

private:
    void copy_finite(float* dst, const std::vector<double>& src, size_t n, const std::string& what,
                     const std::string& label);

    float finite_factor(double v, const std::string& what, const std::string& label);
    void convert_specular(const tinygltf::Material& g, const std::string& label, dev::Material& m);

    dev::Material convert_material(int index);

    // -- textures --

    int32_t texture_for(const tinygltf::TextureInfo& info, const std::string& label);

    int32_t convert_texture(int index);

    // Texels are stored top row first, so glTF's (u, v) (origin top left) index them directly.
    void append_linear_texels(const tinygltf::Image& img);

    uint32_t wrap_bits(int sampler, const std::string& label);

    const tinygltf::Model& m_;
    LoadContext& ctx_;
    Scene& s_;
    int default_material_ = -1;
    std::map<int, int32_t> texture_cache_;
};

} // namespace clppm::gltf
