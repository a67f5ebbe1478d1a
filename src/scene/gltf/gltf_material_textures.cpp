// The textures of glTF materials -> dev::Texture: texture references (texCoord, KHR_texture_transform)
// resolved to scene textures, each glTF texture's texels decoded once per colour space, and its
// sampler's wrap and filter bits (docs/scenes.md, "Materials"). Part of MaterialConverter
// (scene/gltf/gltf_materials.h).
#include "scene/gltf/gltf_materials.h"

#include "scene/texture_sampling.h"

#include <array>
#include <cmath>

namespace clppm::gltf {

namespace {

// 8-bit sRGB -> linear (IEC 61966-2-1).
const std::array<float, 256>& srgb_to_linear_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            double c = i / 255.0;
            t[size_t(i)] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}

} // namespace

int32_t MaterialConverter::texture_for(const tinygltf::TextureInfo& info, const std::string& label,
                                       const std::string& what, bool srgb) {
    return texture_reference(info.index, info.texCoord, info.extensions, label, what, srgb);
}

int32_t MaterialConverter::normal_texture(const tinygltf::NormalTextureInfo& info, const std::string& label) {
    return texture_reference(info.index, info.texCoord, info.extensions, label, "normalTexture", false);
}

int32_t MaterialConverter::texture_reference(int index, int tex_coord, const tinygltf::ExtensionMap& extensions,
                                             const std::string& label, const std::string& what, bool srgb) {
    if (index < 0) return -1;
    if (size_t(index) >= m_.textures.size())
        ctx_.fail(label + " " + what + " " + std::to_string(index) + " out of range");
    std::array<float, 6> xform = {1, 0, 0, 0, 1, 0};
    auto transform = extensions.find("KHR_texture_transform");
    if (transform != extensions.end()) xform = texture_transform(transform->second, label + " " + what, &tex_coord);
    if (tex_coord != 0 && tex_coord != 1) {
        ctx_.warn(label + " " + what + " uses TEXCOORD_" + std::to_string(tex_coord) +
                  "; only TEXCOORD_0 and TEXCOORD_1 are read, texture ignored");
        return -1;
    }
    // Colour textures are decoded from sRGB, data textures (metallic-roughness, normals) are
    // not: one image used both ways is stored twice. References that differ only in their
    // coordinate set or transform share the texels.
    const std::pair<int, bool> image_key{index, srgb};
    auto image = image_cache_.find(image_key);
    if (image == image_cache_.end()) image = image_cache_.emplace(image_key, convert_texture(index, srgb)).first;
    if (!image->second) return -1;
    const TextureKey key{index, srgb, tex_coord, xform};
    auto cached = texture_cache_.find(key);
    if (cached != texture_cache_.end()) return cached->second;
    dev::Texture tex = *image->second;
    std::copy(xform.begin(), xform.end(), tex.xform);
    tex.texcoord = uint32_t(tex_coord);
    uses_texcoord1_ = uses_texcoord1_ || tex_coord == 1;
    s_.textures.push_back(tex);
    return texture_cache_[key] = int32_t(s_.textures.size() - 1);
}

// KHR_texture_transform: u' = T R S u with offset T, scale S and R turning the coordinates by
// `rotation` as the extension's example reads it (offset (0, 1), rotation pi/2, scale 0.5 selects
// the lower left quadrant turned 90 degrees clockwise): u' = sx cos u + sy sin v + ox,
// v' = -sx sin u + sy cos v + oy. Its texCoord, when given, replaces the reference's.
std::array<float, 6> MaterialConverter::texture_transform(const tinygltf::Value& ext, const std::string& what,
                                                          int* tex_coord) {
    if (!ext.IsObject()) ctx_.fail(what + " KHR_texture_transform is not an object");
    auto pair = [&](const char* key, double fallback, double out[2]) {
        out[0] = out[1] = fallback;
        if (!ext.Has(key)) return;
        const tinygltf::Value& v = ext.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
            ctx_.fail(what + " KHR_texture_transform " + key + " must be two numbers");
        out[0] = v.Get(0).GetNumberAsDouble(), out[1] = v.Get(1).GetNumberAsDouble();
    };
    double offset[2], scale[2];
    pair("offset", 0.0, offset);
    pair("scale", 1.0, scale);
    double r = 0;
    if (ext.Has("rotation")) {
        if (!ext.Get("rotation").IsNumber()) ctx_.fail(what + " KHR_texture_transform rotation must be a number");
        r = ext.Get("rotation").GetNumberAsDouble();
    }
    if (ext.Has("texCoord")) {
        if (!ext.Get("texCoord").IsInt()) ctx_.fail(what + " KHR_texture_transform texCoord must be an integer");
        *tex_coord = ext.Get("texCoord").GetNumberAsInt();
    }
    const double c = std::cos(r), s = std::sin(r);
    std::array<float, 6> m = {narrow_to_float(scale[0] * c), narrow_to_float(scale[1] * s),
                              narrow_to_float(offset[0]),    narrow_to_float(-scale[0] * s),
                              narrow_to_float(scale[1] * c), narrow_to_float(offset[1])};
    for (float x : m)
        if (!std::isfinite(x)) ctx_.fail(what + " KHR_texture_transform is not finite");
    return m;
}

std::optional<dev::Texture> MaterialConverter::convert_texture(int index, bool srgb) {
    const tinygltf::Texture& t = m_.textures[size_t(index)];
    std::string label = labelled("texture", index, t.name);
    // EXT_texture_webp names the WebP image; `source`, when present, is a fallback for viewers
    // without WebP.
    int source = t.source;
    auto webp = t.extensions.find("EXT_texture_webp");
    if (webp != t.extensions.end() && webp->second.IsObject() && webp->second.Has("source") &&
        webp->second.Get("source").IsInt())
        source = webp->second.Get("source").GetNumberAsInt();
    if (source < 0 || size_t(source) >= m_.images.size()) {
        ctx_.warn(label + " has no valid image source; texture ignored");
        return std::nullopt;
    }
    const tinygltf::Image& img = m_.images[size_t(source)];
    size_t texels = (img.width > 0 && img.height > 0) ? size_t(img.width) * size_t(img.height) : 0;
    if (texels == 0 || img.component != 4 || img.bits != 8 || img.image.size() != texels * 4) {
        ctx_.warn(label + " image " + std::to_string(source) + " has no decoded pixels; texture ignored");
        return std::nullopt;
    }
    if (s_.texels.size() + texels > kMaxTexels) ctx_.fail("textures exceed 2^26 texels in total");
    dev::Texture tex =
        plain_texture(uint32_t(s_.texels.size()), uint32_t(img.width), uint32_t(img.height), sampler_bits(t.sampler));
    append_texels(img, srgb);
    return tex;
}

// Texels are stored top row first, so glTF's (u, v) (origin top left) index them directly;
// RGB decoded from sRGB when srgb, else taken as linear 8-bit values (alpha is always linear).
void MaterialConverter::append_texels(const tinygltf::Image& img, bool srgb) {
    const auto& lut = srgb_to_linear_table();
    const unsigned char* p = img.image.data();
    for (size_t i = 0, n = img.image.size() / 4; i < n; ++i, p += 4) {
        if (srgb) s_.texels.push_back({lut[p[0]], lut[p[1]], lut[p[2]], p[3] / 255.f});
        else s_.texels.push_back({p[0] / 255.f, p[1] / 255.f, p[2] / 255.f, p[3] / 255.f});
    }
}

// The sampler's wrap modes, and magFilter NEAREST. minFilter is not read: every pixel averages
// many samples over its footprint (docs/scenes.md, "Materials"), so a minified texture converges to
// its area average whatever the mip filter would have approximated.
uint32_t MaterialConverter::sampler_bits(int sampler) {
    if (sampler < 0 || size_t(sampler) >= m_.samplers.size()) return 0; // repeat, linear
    const tinygltf::Sampler& s = m_.samplers[size_t(sampler)];
    return (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? TEXTURE_NEAREST : 0u) |
           (s.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ? TEXTURE_CLAMP_S : 0u) |
           (s.wrapT == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ? TEXTURE_CLAMP_T : 0u) |
           (s.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TEXTURE_MIRROR_S : 0u) |
           (s.wrapT == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TEXTURE_MIRROR_T : 0u);
}
} // namespace clppm::gltf
