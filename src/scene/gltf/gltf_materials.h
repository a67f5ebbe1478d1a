// glTF materials and their textures -> dev::Material and dev::Texture, as docs/scenes.md maps them:
// factors checked finite and clamped, the material kind from metallic, roughness and
// transmission, base colour textures decoded from sRGB, metallic-roughness textures linear.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
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
    void convert_alpha(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_volume(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_unlit(dev::Material& m);
    void convert_clearcoat(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_sheen(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_iridescence(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_anisotropy(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_diffuse_transmission(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_dispersion(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    void convert_volume_scatter(const tinygltf::Material& g, const std::string& label, dev::Material& m);
    int32_t extension_texture(const tinygltf::Material& g, const char* extension, const char* key,
                              const std::string& label, bool srgb);

    dev::Material convert_material(int index);
    float emission_spread(const tinygltf::Material& g, const std::string& label);

    // -- textures --

    // The scene texture of a material's texture reference `what` (-1: none or unusable), decoded
    // from sRGB for colour (srgb) and kept linear for data.
    int32_t texture_for(const tinygltf::TextureInfo& info, const std::string& label, const std::string& what,
                        bool srgb);
    // normalTexture (linear).
    int32_t normal_texture(const tinygltf::NormalTextureInfo& info, const std::string& label);
    int32_t texture_reference(int index, int tex_coord, const tinygltf::ExtensionMap& extensions,
                              const std::string& label, const std::string& what, bool srgb);

    // The texels of glTF texture `index` appended to the scene; nullopt (with a warning) when
    // its image is unusable.
    std::optional<dev::Texture> convert_texture(int index, bool srgb);
    std::array<float, 6> texture_transform(const tinygltf::Value& ext, const std::string& what, int* tex_coord);

    void append_texels(const tinygltf::Image& img, bool srgb);

    uint32_t sampler_bits(int sampler);

    const tinygltf::Model& m_;
    LoadContext& ctx_;
    Scene& s_;
    int default_material_ = -1;
    std::map<std::pair<int, bool>, std::optional<dev::Texture>> image_cache_; // (glTF texture, sRGB) -> texels
    using TextureKey = std::tuple<int, bool, int, std::array<float, 6>>;      // + texCoord, transform
    std::map<TextureKey, int32_t> texture_cache_;                             // -> scene texture
    bool uses_texcoord1_ = false;

public:
    // Some texture reference reads TEXCOORD_1 (known once convert_materials has run).
    bool uses_texcoord1() const { return uses_texcoord1_; }
};

} // namespace clppm::gltf
