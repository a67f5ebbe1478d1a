#include "scene/gltf/gltf_variants.h"

namespace clppm::gltf {

namespace {

constexpr const char* kExt = "KHR_materials_variants";

std::string names_text(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s.empty() ? "none" : s;
}

} // namespace

void apply_material_variant(tinygltf::Model& model, const std::string& variant, LoadContext& ctx, Scene& scene) {
    auto root = model.extensions.find(kExt);
    if (root != model.extensions.end()) {
        const tinygltf::Value& list = root->second.Get("variants");
        if (!list.IsArray()) ctx.fail(std::string(kExt) + ": \"variants\" must be an array");
        for (size_t i = 0; i < list.ArrayLen(); ++i) {
            const tinygltf::Value& name = list.Get(int(i)).Get("name");
            if (!name.IsString()) ctx.fail(std::string(kExt) + ": variant " + std::to_string(i) + " has no name");
            scene.variants.push_back(printable(name.Get<std::string>()));
        }
    }
    int index = -1;
    if (!variant.empty()) {
        for (size_t i = 0; i < scene.variants.size(); ++i)
            if (scene.variants[i] == variant) index = int(i);
        if (index < 0)
            ctx.fail("--variant " + printable(variant) +
                     ": no such material variant (the file's: " + names_text(scene.variants) + ")");
        scene.variant = variant;
    }
    // Every mapping is checked, whether or not a variant is rendered: a broken one is a broken file.
    for (size_t m = 0; m < model.meshes.size(); ++m)
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            tinygltf::Primitive& prim = model.meshes[m].primitives[p];
            auto ext = prim.extensions.find(kExt);
            if (ext == prim.extensions.end()) continue;
            const std::string label = "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + ": " + kExt;
            const tinygltf::Value& mappings = ext->second.Get("mappings");
            if (!mappings.IsArray()) ctx.fail(label + " \"mappings\" must be an array");
            for (size_t k = 0; k < mappings.ArrayLen(); ++k) {
                const tinygltf::Value& mapping = mappings.Get(int(k));
                const tinygltf::Value& material = mapping.Get("material");
                const tinygltf::Value& variants = mapping.Get("variants");
                const std::string what = label + " mapping " + std::to_string(k);
                if (!material.IsInt() || material.Get<int>() < 0 ||
                    size_t(material.Get<int>()) >= model.materials.size())
                    ctx.fail(what + " names material " +
                             (material.IsInt() ? std::to_string(material.Get<int>()) : std::string("(not an index)")) +
                             ", but the file has " + std::to_string(model.materials.size()));
                if (!variants.IsArray()) ctx.fail(what + " has no variants");
                for (size_t v = 0; v < variants.ArrayLen(); ++v) {
                    const tinygltf::Value& i = variants.Get(int(v));
                    if (!i.IsInt() || i.Get<int>() < 0 || size_t(i.Get<int>()) >= scene.variants.size())
                        ctx.fail(what + " names variant " +
                                 (i.IsInt() ? std::to_string(i.Get<int>()) : std::string("(not an index)")) +
                                 ", but the file has " + std::to_string(scene.variants.size()));
                    if (i.Get<int>() == index) prim.material = material.Get<int>();
                }
            }
        }
}

} // namespace clppm::gltf
