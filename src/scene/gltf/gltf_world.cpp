#include "scene/gltf/gltf_world.h"

#include <cmath>
#include <filesystem>

#include "scene/gltf/gltf_files.h"

namespace clppm::gltf {

namespace {

constexpr const char* kKey = "extras.clppm_environment";

double number(const tinygltf::Value& v, const std::string& what, LoadContext& ctx, bool non_negative) {
    if (!v.IsNumber()) ctx.fail(std::string(kKey) + "." + what + " must be a number");
    const double x = v.GetNumberAsDouble();
    if (!std::isfinite(x) || (non_negative && x < 0))
        ctx.fail(std::string(kKey) + "." + what + " must be a finite number" + (non_negative ? " >= 0" : ""));
    return x;
}

} // namespace

void read_file_world(const tinygltf::Model& model, const std::string& base, LoadContext& ctx, Scene& scene) {
    const tinygltf::Value* entry = scene_extra(model, "clppm_environment");
    if (!entry) return;
    const tinygltf::Value& e = *entry;
    if (!e.IsObject()) ctx.fail(std::string(kKey) + " must be an object: {\"color\": [r, g, b]} or {\"image\": URI}");
    for (const std::string& key : e.Keys())
        if (key != "color" && key != "image" && key != "strength" && key != "rotation")
            ctx.fail(std::string(kKey) + ": unknown key \"" + key + "\" (color, image, strength, rotation)");
    FileWorld w;
    if (e.Has("color") == e.Has("image")) ctx.fail(std::string(kKey) + " must have either \"color\" or \"image\"");
    if (e.Has("color")) {
        const tinygltf::Value& c = e.Get("color");
        if (!c.IsArray() || c.ArrayLen() != 3) ctx.fail(std::string(kKey) + ".color must be [r, g, b]");
        w.kind = FileWorld::Kind::Color;
        for (int i = 0; i < 3; ++i) w.color[size_t(i)] = float(number(c.Get(i), "color", ctx, true));
    } else {
        const tinygltf::Value& uri = e.Get("image");
        if (!uri.IsString() || uri.Get<std::string>().empty())
            ctx.fail(std::string(kKey) + ".image must be a file name relative to the scene");
        if (base.empty()) ctx.fail(std::string(kKey) + ".image: this scene has no folder to find it in");
        const std::string path = (std::filesystem::path(base) / uri.Get<std::string>()).lexically_normal().string();
        if (!path_inside(path, base) || !resolves_inside(path, base))
            ctx.fail(std::string(kKey) + ".image " + uri.Get<std::string>() + " lies outside the scene's folder");
        w.kind = FileWorld::Kind::Image;
        w.image = path;
    }
    if (e.Has("strength")) w.strength = number(e.Get("strength"), "strength", ctx, true);
    if (e.Has("rotation")) w.rotation_degrees = number(e.Get("rotation"), "rotation", ctx, false);
    scene.file_world = w;
}

} // namespace clppm::gltf
