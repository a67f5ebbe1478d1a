#include "scene/gltf/gltf_medium.h"

#include <cmath>

#include "util/text.h"

namespace clppm::gltf {

namespace {

constexpr const char* kKey = "extras.clppm_medium";

// A number, or [r, g, b], each finite and within [lo, hi] (hi_open: below hi).
std::array<float, 3> rgb_or_number(const tinygltf::Value& v, const std::string& what, double lo, double hi,
                                   LoadContext& ctx) {
    const std::string name = std::string(kKey) + "." + what;
    std::array<float, 3> out{};
    auto one = [&](const tinygltf::Value& x) {
        if (!x.IsNumber()) ctx.fail(name + " must be a number or [r, g, b]");
        const double d = x.GetNumberAsDouble();
        if (!std::isfinite(d) || d < lo || d > hi || !std::isfinite(float(d)))
            ctx.fail(name + " must be finite, from " + number_text(lo) + " to " + number_text(hi));
        return float(d);
    };
    if (v.IsArray()) {
        if (v.ArrayLen() != 3) ctx.fail(name + " must be a number or [r, g, b]");
        for (int k = 0; k < 3; ++k) out[size_t(k)] = one(v.Get(k));
    } else {
        out[0] = out[1] = out[2] = one(v);
    }
    return out;
}

} // namespace

void read_file_medium(const tinygltf::Model& model, LoadContext& ctx, Scene& scene) {
    const tinygltf::Value* entry = scene_extra(model, "clppm_medium");
    if (!entry) return;
    const tinygltf::Value& e = *entry;
    if (!e.IsObject())
        ctx.fail(std::string(kKey) + " must be an object: {\"density\": D, \"albedo\": [r, g, b], \"anisotropy\": g}");
    for (const std::string& key : e.Keys())
        if (key != "density" && key != "albedo" && key != "anisotropy")
            ctx.fail(std::string(kKey) + ": unknown key \"" + key + "\" (density, albedo, anisotropy)");
    if (!e.Has("density")) ctx.fail(std::string(kKey) + " must have a \"density\" (extinction per scene unit)");
    MediumDesc m;
    m.density = rgb_or_number(e.Get("density"), "density", 0.0, 3e38, ctx);
    if (e.Has("albedo")) m.albedo = rgb_or_number(e.Get("albedo"), "albedo", 0.0, 1.0, ctx);
    if (e.Has("anisotropy")) {
        const tinygltf::Value& g = e.Get("anisotropy");
        const double d = g.IsNumber() ? g.GetNumberAsDouble() : NAN;
        if (!(d > -1.0 && d < 1.0)) ctx.fail(std::string(kKey) + ".anisotropy must be a number above -1 and below 1");
        m.anisotropy = float(d);
    }
    scene.has_file_medium = true;
    scene.file_medium = m;
}

} // namespace clppm::gltf
