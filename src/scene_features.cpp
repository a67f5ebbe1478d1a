#include "scene_features.h"

namespace clppm {

SceneFeatures scene_features(const Scene& scene, const DeviceScene& ds) {
    SceneFeatures f;
    // Only materials some triangle uses count.
    std::vector<bool> used(scene.materials.size(), false);
    for (const dev::TriShading& t : scene.shading)
        if (t.material < used.size()) used[t.material] = true;
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const dev::Material& m = scene.materials[i];
        const bool metal_is_glossy = m.roughness > 0.f;
        switch (m.kind) {
        case MATERIAL_MIRROR: f.mirror = true; break;
        case MATERIAL_GLOSSY: f.glossy = true; break;
        case MATERIAL_DIELECTRIC: f.dielectric = true; break;
        case MATERIAL_METAL_MIX:
            f.metal_mix = true;
            (metal_is_glossy ? f.glossy : f.mirror) = true;
            break;
        default: break;
        }
        if (m.base_color_tex >= 0) f.textures = true;
    }
    for (const dev::Light& l : ds.lights) {
        if (l.type == LIGHT_TRIANGLE) f.area_lights = true;
        if (l.type == LIGHT_POINT) f.point_lights = true;
        if (l.type == LIGHT_SPOT) f.spot_lights = true;
        if (l.type == LIGHT_DIRECTIONAL) f.directional_lights = true;
    }
    f.thin_lens = ds.camera.lens_radius > 0.f;
    return f;
}

std::string feature_build_options(const SceneFeatures& f) {
    std::string o;
    auto off = [&](bool present, const char* name) {
        if (!present) o += std::string(o.empty() ? "" : " ") + "-D" + name + "=0";
    };
    off(f.mirror, "HAS_MIRROR");
    off(f.glossy, "HAS_GLOSSY");
    off(f.dielectric, "HAS_DIELECTRIC");
    off(f.metal_mix, "HAS_METAL_MIX");
    off(f.textures, "HAS_TEXTURES");
    off(f.area_lights, "HAS_AREA_LIGHTS");
    off(f.point_lights, "HAS_POINT_LIGHTS");
    off(f.spot_lights, "HAS_SPOT_LIGHTS");
    off(f.directional_lights, "HAS_DIRECTIONAL_LIGHTS");
    off(f.thin_lens, "HAS_THIN_LENS");
    return o;
}

std::string describe_features(const SceneFeatures& f) {
    std::string s = "diffuse";
    auto add = [&](bool present, const char* name) {
        if (present) s += std::string(", ") + name;
    };
    add(f.mirror, "mirror");
    add(f.glossy, "glossy");
    add(f.dielectric, "dielectric");
    add(f.metal_mix, "metal mix");
    add(f.textures, "textures");
    add(f.area_lights, "area lights");
    add(f.point_lights, "point lights");
    add(f.spot_lights, "spot lights");
    add(f.directional_lights, "directional lights");
    add(f.thin_lens, "thin lens");
    return s;
}

} // namespace clppm
