// glTF 2.0 -> Scene. Three stages: a guarded pre-scan of the raw JSON (nesting depth, required
// extensions, URIs, image buffer views: the checks tinygltf does not make before it touches
// memory or the file system), parsing with tinygltf behind file-system callbacks that stay inside
// the scene's directory, decoding Draco-compressed primitives, posing the nodes at the start of the
// first animation, then flattening the node hierarchy into world-space triangles.
#include "scene/gltf/gltf_load.h"

#include <filesystem>

#include "scene/gltf/gltf_animation_pose.h"
#include "scene/gltf/gltf_context.h"
#include "scene/gltf/gltf_draco.h"
#include "scene/gltf/gltf_files.h"
#include "scene/gltf/gltf_medium.h"
#include "scene/gltf/gltf_parse.h"
#include "scene/gltf/gltf_scene_builder.h"
#include "scene/gltf/gltf_spec_gloss.h"
#include "scene/gltf/gltf_variants.h"
#include "scene/gltf/gltf_world.h"
#include "util/embedded_files.h"
#include "util/error.h"

namespace clppm {

namespace {

namespace fs = std::filesystem;
using namespace gltf;

Scene load_bytes(const std::vector<unsigned char>& bytes, const std::string& base, const std::string& source,
                 const std::string& variant) {
    Scene scene;
    scene.source = source;
    LoadContext ctx(source, &scene);
    tinygltf::Model model = parse_model(bytes, base, ctx);
    decode_draco_primitives(model, ctx);
    apply_material_variant(model, variant, ctx, scene);
    apply_animation_start(model, ctx);
    if (const int n = convert_specular_glossiness(model, ctx))
        ctx.warn(std::to_string(n) +
                 " material(s) in KHR_materials_pbrSpecularGlossiness (archived) converted to "
                 "metallic-roughness with KHR_materials_specular: F0 = the specular colour, roughness = 1 - "
                 "glossiness (docs/scenes.md, \"Scenes and conventions\")");
    SceneBuilder(model, ctx, scene).build();
    read_file_world(model, base, ctx, scene);
    read_file_medium(model, ctx, scene);
    return scene;
}

} // namespace

Scene load_gltf(const std::string& path, const std::string& variant) {
    std::string why;
    std::vector<unsigned char> bytes = read_whole_file(path, &why);
    if (!why.empty()) throw Error(path + ": cannot open file (" + why + ")");
    return load_bytes(bytes, absolute_dir(fs::path(path).parent_path().string()), path, variant);
}

Scene load_gltf_text(const std::string& json_text, const std::string& base_dir, const std::string& display_name) {
    if (json_text.size() > kMaxFileBytes) throw Error(display_name + ": larger than 1 GiB");
    std::vector<unsigned char> bytes(json_text.begin(), json_text.end());
    return load_bytes(bytes, base_dir.empty() ? std::string() : absolute_dir(base_dir), display_name, "");
}

Scene load_default_scene() {
    const char* name = "<default scene>";
    const EmbeddedFile* file = find_embedded("scenes/cornell_box.gltf");
    if (!file) throw Error(std::string(name) + ": scenes/cornell_box.gltf is not embedded in this build");
    return load_gltf_text(std::string(file->data, file->size), "", name);
}

} // namespace clppm
