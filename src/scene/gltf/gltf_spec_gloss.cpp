#include "scene/gltf/gltf_spec_gloss.h"

#include <algorithm>
#include <cmath>

namespace clppm::gltf {

namespace {

constexpr const char* kExt = "KHR_materials_pbrSpecularGlossiness";
constexpr double kIor = 1000.0;

std::vector<double> numbers(const tinygltf::Value& v, const char* key, std::vector<double> fallback,
                            const std::string& label, LoadContext& ctx) {
    if (!v.Has(key)) return fallback;
    const tinygltf::Value& a = v.Get(key);
    if (fallback.size() == 1) {
        if (!a.IsNumber()) ctx.fail(label + " " + kExt + " " + key + " must be a number");
        return {a.GetNumberAsDouble()};
    }
    if (!a.IsArray() || a.ArrayLen() != fallback.size())
        ctx.fail(label + " " + kExt + " " + key + " must have " + std::to_string(fallback.size()) + " numbers");
    std::vector<double> out(fallback.size());
    for (size_t i = 0; i < out.size(); ++i) {
        if (!a.Get(int(i)).IsNumber()) ctx.fail(label + " " + kExt + " " + key + " must hold numbers");
        out[i] = a.Get(int(i)).GetNumberAsDouble();
        if (!std::isfinite(out[i])) ctx.fail(label + " " + kExt + " " + key + " must be finite");
    }
    return out;
}

// A texture reference of the extension ({"index", "texCoord", "extensions"}) as a TextureInfo.
tinygltf::TextureInfo texture_info(const tinygltf::Value& v, const char* key, const std::string& label,
                                   LoadContext& ctx) {
    tinygltf::TextureInfo t;
    const tinygltf::Value& ti = v.Get(key);
    if (!ti.IsObject() || !ti.Has("index") || !ti.Get("index").IsInt())
        ctx.fail(label + " " + kExt + " " + key + " has no texture index");
    t.index = ti.Get("index").GetNumberAsInt();
    t.texCoord = ti.Has("texCoord") && ti.Get("texCoord").IsInt() ? ti.Get("texCoord").GetNumberAsInt() : 0;
    if (ti.Has("extensions") && ti.Get("extensions").IsObject() && ti.Get("extensions").Has("KHR_texture_transform"))
        t.extensions["KHR_texture_transform"] = ti.Get("extensions").Get("KHR_texture_transform");
    return t;
}

tinygltf::Value texture_value(const tinygltf::TextureInfo& t) {
    tinygltf::Value::Object o{{"index", tinygltf::Value(t.index)}, {"texCoord", tinygltf::Value(t.texCoord)}};
    if (!t.extensions.empty()) {
        tinygltf::Value::Object ext;
        for (const auto& [k, v] : t.extensions) ext[k] = v;
        o["extensions"] = tinygltf::Value(ext);
    }
    return tinygltf::Value(o);
}

tinygltf::Value array3(const double v[3]) {
    return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(v[0]), tinygltf::Value(v[1]), tinygltf::Value(v[2])});
}

// A new texture whose G channel is 1 - glossiness (alpha of texture `index` times `glossiness`),
// in the same sampler; -1 where the image has no decoded pixels (the loader then warns).
int roughness_texture(tinygltf::Model& model, int index, double glossiness) {
    if (index < 0 || size_t(index) >= model.textures.size()) return -1;
    const tinygltf::Texture src = model.textures[size_t(index)];
    if (src.source < 0 || size_t(src.source) >= model.images.size()) return -1;
    const tinygltf::Image& img = model.images[size_t(src.source)];
    if (img.component != 4 || img.bits != 8 || img.image.size() != size_t(img.width) * size_t(img.height) * 4)
        return -1;
    tinygltf::Image rough;
    rough.name = img.name + " (roughness from glossiness)";
    rough.width = img.width, rough.height = img.height, rough.component = 4, rough.bits = 8;
    rough.pixel_type = img.pixel_type;
    rough.image.resize(img.image.size());
    for (size_t i = 0; i < img.image.size(); i += 4) {
        const double gloss = std::clamp(glossiness * img.image[i + 3] / 255.0, 0.0, 1.0);
        rough.image[i] = 0;
        rough.image[i + 1] = static_cast<unsigned char>(std::lround(255.0 * (1.0 - gloss)));
        rough.image[i + 2] = 0; // metallic 0 (metallicFactor is 0 anyway)
        rough.image[i + 3] = 255;
    }
    model.images.push_back(std::move(rough));
    tinygltf::Texture t;
    t.sampler = src.sampler;
    t.source = int(model.images.size()) - 1;
    model.textures.push_back(t);
    return int(model.textures.size()) - 1;
}

} // namespace

int convert_specular_glossiness(tinygltf::Model& model, LoadContext& ctx) {
    int converted = 0;
    const double f0_ior = std::pow((kIor - 1) / (kIor + 1), 2);
    for (size_t i = 0; i < model.materials.size(); ++i) {
        tinygltf::Material& m = model.materials[i];
        auto it = m.extensions.find(kExt);
        if (it == m.extensions.end()) continue;
        const tinygltf::Value v = it->second;
        const std::string label = labelled("material", int(i), m.name);
        if (!v.IsObject()) ctx.fail(label + " " + kExt + " must be an object");
        const std::vector<double> diffuse = numbers(v, "diffuseFactor", {1, 1, 1, 1}, label, ctx);
        const std::vector<double> specular = numbers(v, "specularFactor", {1, 1, 1}, label, ctx);
        const double glossiness = numbers(v, "glossinessFactor", {1}, label, ctx)[0];
        tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        pbr.baseColorFactor = diffuse;
        pbr.baseColorTexture =
            v.Has("diffuseTexture") ? texture_info(v, "diffuseTexture", label, ctx) : tinygltf::TextureInfo();
        pbr.metallicFactor = 0.0;
        pbr.roughnessFactor = 1.0 - std::clamp(glossiness, 0.0, 1.0);
        pbr.metallicRoughnessTexture = tinygltf::TextureInfo();
        const double color[3] = {specular[0] / f0_ior, specular[1] / f0_ior, specular[2] / f0_ior};
        tinygltf::Value::Object spec{{"specularFactor", tinygltf::Value(1.0)}, {"specularColorFactor", array3(color)}};
        if (v.Has("specularGlossinessTexture")) {
            const tinygltf::TextureInfo sg = texture_info(v, "specularGlossinessTexture", label, ctx);
            spec["specularColorTexture"] = texture_value(sg);
            const int rough = roughness_texture(model, sg.index, glossiness);
            if (rough >= 0) {
                pbr.roughnessFactor = 1.0;
                pbr.metallicRoughnessTexture = sg;
                pbr.metallicRoughnessTexture.index = rough;
            } else {
                ctx.warn(label + " " + kExt + ": specularGlossinessTexture has no decoded pixels; glossiness is " +
                         "glossinessFactor alone");
            }
        }
        m.extensions.erase(kExt);
        m.extensions["KHR_materials_specular"] = tinygltf::Value(spec);
        m.extensions["KHR_materials_ior"] = tinygltf::Value(tinygltf::Value::Object{{"ior", tinygltf::Value(kIor)}});
        ++converted;
    }
    return converted;
}

} // namespace clppm::gltf
