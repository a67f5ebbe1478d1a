#include "scene/scene_features.h"

#include "scene/used_materials.h"

namespace clppm {

SceneFeatures scene_features(const Scene& scene, const DeviceScene& ds) {
    SceneFeatures f;
    // Only materials some triangle uses count.
    const std::vector<bool> used = used_materials(scene);
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const dev::Material& m = scene.materials[i];
        // The lobes of kernels/bsdf.cl this material gives weight to somewhere: textures only
        // scale metallic (metallicRoughnessTexture B) and transmission (transmissionTexture R)
        // down, so with one they may reach 0 and the dielectric base its full weight.
        const float metallic_min = m.metallic_roughness_tex >= 0 ? 0.f : m.metallic;
        const float transmission_min = m.transmission_tex >= 0 ? 0.f : m.transmission;
        const float dielectric = (1.f - metallic_min) * (1.f - transmission_min);
        if (dielectric > 0.f && m.specular_color[3] > 0.f) f.specular_layer = true;
        if (m.metallic > 0.f) f.metal = true;
        if (m.transmission > 0.f && metallic_min < 1.f) f.glass = true;
        // Textures only lower roughness: a factor of 0 keeps every glass surface smooth.
        if (m.transmission > 0.f && metallic_min < 1.f && m.roughness > 0.f) f.rough_glass = true;
        if (m.base_color_tex >= 0 || m.metallic_roughness_tex >= 0 || m.emissive_tex >= 0) f.textures = true;
        if (m.normal_tex >= 0 && !scene.tangents.empty()) f.textures = f.normal_maps = true;
        if (m.alpha_mode != ALPHA_OPAQUE) f.alpha = true;
        // Diffuse transmission acts on the dielectric base only.
        const bool translucent = m.diffuse_transmission > 0.f && metallic_min < 1.f && transmission_min < 1.f;
        if (translucent) f.diffuse_transmission = true;
        if (translucent && (m.diffuse_transmission_tex >= 0 || m.diffuse_transmission_color_tex >= 0))
            f.textures = true;
        if ((m.transmission > 0.f || translucent) &&
            (m.attenuation[0] > 0.f || m.attenuation[1] > 0.f || m.attenuation[2] > 0.f))
            f.volume = true;
        if (m.dispersion > 0.f && m.transmission > 0.f && metallic_min < 1.f) f.dispersion = true;
        if (m.transmission_tex >= 0 || m.specular_tex >= 0 || m.specular_color_tex >= 0) f.textures = true;
        if (m.emission_spread > 0.f) f.emission_spread = true;
        if (m.flags & MATERIAL_FLAG_UNLIT) f.unlit = true;
        if (m.clearcoat > 0.f) f.clearcoat = true;
        const bool sheen = m.sheen_color[0] > 0.f || m.sheen_color[1] > 0.f || m.sheen_color[2] > 0.f;
        if (sheen) f.sheen = true;
        // The film acts on the specular layer and the metal only.
        if (m.iridescence > 0.f && ((dielectric > 0.f && m.specular_color[3] > 0.f) || m.metallic > 0.f))
            f.iridescence = true;
        if (m.iridescence > 0.f && (m.iridescence_tex >= 0 || m.iridescence_thickness_tex >= 0)) f.textures = true;
        // The lobes it stretches: the layer, the metal, rough glass.
        if (m.anisotropy_strength > 0.f && (dielectric > 0.f || m.metallic > 0.f || m.transmission > 0.f)) {
            f.anisotropy = true;
            if (m.anisotropy_tex >= 0) f.textures = true;
        }
        if (sheen && (m.sheen_color_tex >= 0 || m.sheen_roughness_tex >= 0)) f.textures = true;
        if (m.clearcoat > 0.f && (m.clearcoat_tex >= 0 || m.clearcoat_roughness_tex >= 0)) f.textures = true;
        if (m.clearcoat > 0.f && m.clearcoat_normal_tex >= 0 && !scene.tangents.empty())
            f.textures = f.normal_maps = true;
    }
    f.vertex_colors = !scene.colors.empty();
    for (const dev::Light& l : ds.lights) {
        if (l.type == LIGHT_TRIANGLE) f.area_lights = true;
        if (l.type == LIGHT_POINT) f.point_lights = true;
        if (l.type == LIGHT_SPOT) f.spot_lights = true;
        if (l.type == LIGHT_DIRECTIONAL) f.directional_lights = true;
        if (l.type == LIGHT_ENVIRONMENT) f.env_light = true;
    }
    f.medium = ds.media;
    f.thin_lens = ds.camera.lens_radius > 0.f;
    f.orthographic = ds.camera.forward[3] != 0.f;
    return f;
}

SceneFeatures SceneFeatures::all() {
    SceneFeatures f;
#define CLPPM_FEATURE_ON(flag, field, text) f.field = true;
    CLPPM_KERNEL_FEATURES(CLPPM_FEATURE_ON)
#undef CLPPM_FEATURE_ON
    return f;
}

std::string feature_build_options(const SceneFeatures& f) {
    std::string o;
#define CLPPM_FEATURE_OPTION(flag, field, text)                                                                        \
    if (!f.field) o += std::string(o.empty() ? "" : " ") + "-D" #flag "=0";
    CLPPM_KERNEL_FEATURES(CLPPM_FEATURE_OPTION)
#undef CLPPM_FEATURE_OPTION
    return o;
}

std::string describe_features(const SceneFeatures& f) {
    std::string s = "diffuse";
#define CLPPM_FEATURE_TEXT(flag, field, text)                                                                          \
    if (f.field) s += std::string(", ") + text;
    CLPPM_KERNEL_FEATURES(CLPPM_FEATURE_TEXT)
#undef CLPPM_FEATURE_TEXT
    return s;
}

} // namespace clppm
