#include "scene/gltf/gltf_materials.h"

#include "scene/material_defaults.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace clppm::gltf {

namespace {

// A number inside a material/texture extension object, or `fallback` when absent.
double extension_number(const tinygltf::ExtensionMap& extensions, const char* extension, const char* key,
                        double fallback) {
    auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& v = it->second.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

} // namespace

void MaterialConverter::convert_materials() {
    for (size_t i = 0; i < m_.materials.size(); ++i) {
        s_.materials.push_back(convert_material(int(i)));
        s_.material_names.push_back(m_.materials[i].name);
    }
}

void MaterialConverter::copy_finite(float* dst, const std::vector<double>& src, size_t n, const std::string& what,
                                    const std::string& label) {
    if (src.size() != n) ctx_.fail(label + " " + what + " must have " + std::to_string(n) + " components");
    for (size_t c = 0; c < n; ++c) {
        dst[c] = narrow_to_float(src[c]);
        if (!std::isfinite(dst[c])) ctx_.fail(label + " has a non-finite " + what);
    }
}

float MaterialConverter::finite_factor(double v, const std::string& what, const std::string& label) {
    float f = narrow_to_float(v);
    if (!std::isfinite(f)) ctx_.fail(label + " has a non-finite " + what);
    return f;
}

// An area light's spread (Blender's, in degrees, in (0, 180]) from the material's extras
// "clppm_area_light_spread": tan of half of it for kernels/scene.cl, 0 for 180 (Lambertian).
float MaterialConverter::emission_spread(const tinygltf::Material& g, const std::string& label) {
    if (!g.extras.IsObject() || !g.extras.Has("clppm_area_light_spread")) return 0.f;
    const tinygltf::Value& v = g.extras.Get("clppm_area_light_spread");
    const double degrees = v.IsNumber() ? v.GetNumberAsDouble() : NAN;
    if (!(degrees > 0.0 && degrees <= 180.0))
        ctx_.fail(label + " extras.clppm_area_light_spread must be a number of degrees in (0, 180]");
    if (degrees >= 180.0) return 0.f;
    return float(std::tan(0.5 * degrees * kPi / 180.0));
}

dev::Material MaterialConverter::convert_material(int index) {
    const tinygltf::Material& g = m_.materials[size_t(index)];
    const auto& pbr = g.pbrMetallicRoughness;
    std::string label = labelled("material", index, g.name);
    dev::Material m{};
    copy_finite(m.base_color, pbr.baseColorFactor, 4, "baseColorFactor", label);
    for (int c = 0; c < 4; ++c) m.base_color[c] = std::clamp(m.base_color[c], 0.f, 1.f);
    copy_finite(m.emission, g.emissiveFactor, 3, "emissiveFactor", label);
    float strength =
        finite_factor(extension_number(g.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0),
                      "emissiveStrength", label);
    bool negative = false;
    for (int c = 0; c < 3; ++c) { // each factor finite as a float, their product may not be
        const float e = finite_factor(double(m.emission[c]) * strength, "emissiveFactor * emissiveStrength", label);
        negative = negative || e < 0.f;
        m.emission[c] = std::max(0.f, e);
    }
    if (negative) ctx_.warn(label + " emissiveFactor * emissiveStrength is negative; that part emits nothing");
    m.emission_spread = emission_spread(g, label);
    m.metallic = std::clamp(finite_factor(pbr.metallicFactor, "metallicFactor", label), 0.f, 1.f);
    m.roughness = std::clamp(finite_factor(pbr.roughnessFactor, "roughnessFactor", label), 0.f, 1.f);
    m.transmission = std::clamp(
        finite_factor(extension_number(g.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0),
                      "transmissionFactor", label),
        0.f, 1.f);
    m.ior = finite_factor(extension_number(g.extensions, "KHR_materials_ior", "ior", 1.5), "ior", label);
    if (m.ior < 1.f) {
        ctx_.warn(label + " ior " + std::to_string(m.ior) + " is below 1; using 1");
        m.ior = 1.f;
    }
    m.base_color_tex = texture_for(pbr.baseColorTexture, label, "baseColorTexture", true);
    m.metallic_roughness_tex = texture_for(pbr.metallicRoughnessTexture, label, "metallicRoughnessTexture", false);
    m.emissive_tex = texture_for(g.emissiveTexture, label, "emissiveTexture", true);
    m.normal_tex = normal_texture(g.normalTexture, label);
    m.normal_scale = finite_factor(g.normalTexture.scale, "normalTexture.scale", label);
    convert_alpha(g, label, m);
    convert_volume(g, label, m);
    convert_specular(g, label, m);
    convert_clearcoat(g, label, m);
    convert_sheen(g, label, m);
    convert_iridescence(g, label, m);
    convert_anisotropy(g, label, m);
    convert_diffuse_transmission(g, label, m);
    // Only light that passes the surface meets the volume: an opaque mesh keeps the world's medium outside.
    if (!(m.transmission > 0.f) && !(m.diffuse_transmission > 0.f)) m.flags &= ~MATERIAL_FLAG_ENCLOSES_VOLUME;
    convert_volume_scatter(g, label, m);
    convert_dispersion(g, label, m);
    if (g.doubleSided) m.flags |= MATERIAL_FLAG_DOUBLE_SIDED;
    if (g.extensions.count("KHR_materials_unlit")) convert_unlit(m);
    return m;
}

// KHR_materials_unlit: the base colour (factor, texture, COLOR_0) shown as it is, not lit; the
// surface scatters nothing (kernels/scene.cl). Alpha and emission keep their meaning; the lobes'
// parameters are cleared so that the kernels are built for what the scene shows.
void MaterialConverter::convert_unlit(dev::Material& m) {
    m.flags |= MATERIAL_FLAG_UNLIT;
    m.metallic = 0.f;
    m.roughness = 1.f;
    m.transmission = 0.f;
    m.specular_color[3] = 0.f;
    m.metallic_roughness_tex = m.normal_tex = m.transmission_tex = m.specular_tex = m.specular_color_tex = -1;
    m.clearcoat = 0.f;
    m.clearcoat_tex = m.clearcoat_roughness_tex = m.clearcoat_normal_tex = -1;
    for (int c = 0; c < 3; ++c) m.sheen_color[c] = 0.f;
    m.sheen_color_tex = m.sheen_roughness_tex = -1;
    m.iridescence = 0.f;
    m.iridescence_tex = m.iridescence_thickness_tex = -1;
    m.anisotropy_strength = 0.f;
    m.anisotropy_tex = -1;
    m.diffuse_transmission = 0.f;
    m.diffuse_transmission_tex = m.diffuse_transmission_color_tex = -1;
    m.dispersion = 0.f;
    for (float& a : m.attenuation) a = 0.f;
    m.flags &= ~MATERIAL_FLAG_THIN_WALLED;
}

// KHR_materials_clearcoat: clearcoatFactor times clearcoatTexture's R weighs a GGX coat of ior 1.5
// (F0 0.04) with alpha = (clearcoatRoughnessFactor times clearcoatRoughnessTexture's G)^2 over the
// rest of the material, on its own normal: clearcoatNormalTexture's, else the smooth surface
// normal (the base's normal map does not tilt the coat). kernels/bsdf.cl has the layering.
void MaterialConverter::convert_clearcoat(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    m.clearcoat_tex = m.clearcoat_roughness_tex = m.clearcoat_normal_tex = -1;
    m.clearcoat_normal_scale = 1.f;
    auto it = g.extensions.find("KHR_materials_clearcoat");
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const char* ext = "KHR_materials_clearcoat";
    m.clearcoat = std::clamp(
        finite_factor(extension_number(g.extensions, ext, "clearcoatFactor", 0.0), "clearcoatFactor", label), 0.f, 1.f);
    m.clearcoat_roughness =
        std::clamp(finite_factor(extension_number(g.extensions, ext, "clearcoatRoughnessFactor", 0.0),
                                 "clearcoatRoughnessFactor", label),
                   0.f, 1.f);
    if (!(m.clearcoat > 0.f)) return;
    m.clearcoat_tex = extension_texture(g, ext, "clearcoatTexture", label, false);
    m.clearcoat_roughness_tex = extension_texture(g, ext, "clearcoatRoughnessTexture", label, false);
    m.clearcoat_normal_tex = extension_texture(g, ext, "clearcoatNormalTexture", label, false);
    const tinygltf::Value& v = it->second;
    if (m.clearcoat_normal_tex >= 0 && v.Get("clearcoatNormalTexture").Has("scale")) {
        const tinygltf::Value& s = v.Get("clearcoatNormalTexture").Get("scale");
        if (!s.IsNumber()) ctx_.fail(label + " clearcoatNormalTexture scale must be a number");
        m.clearcoat_normal_scale = finite_factor(s.GetNumberAsDouble(), "clearcoatNormalTexture.scale", label);
    }
}

// KHR_materials_sheen: sheenColorFactor times sheenColorTexture (sRGB) and sheenRoughnessFactor
// times sheenRoughnessTexture's A (linear); kernels/bsdf.cl has the lobe and the albedo scaling.
void MaterialConverter::convert_sheen(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    m.sheen_color_tex = m.sheen_roughness_tex = -1;
    auto it = g.extensions.find("KHR_materials_sheen");
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const char* ext = "KHR_materials_sheen";
    const tinygltf::Value& v = it->second;
    if (v.Has("sheenColorFactor")) {
        const tinygltf::Value& c = v.Get("sheenColorFactor");
        if (!c.IsArray() || c.ArrayLen() != 3) ctx_.fail(label + " sheenColorFactor must have 3 components");
        for (int k = 0; k < 3; ++k) {
            if (!c.Get(k).IsNumber()) ctx_.fail(label + " sheenColorFactor must have 3 numbers");
            m.sheen_color[k] =
                std::clamp(finite_factor(c.Get(k).GetNumberAsDouble(), "sheenColorFactor", label), 0.f, 1.f);
        }
    }
    m.sheen_roughness = std::clamp(
        finite_factor(extension_number(g.extensions, ext, "sheenRoughnessFactor", 0.0), "sheenRoughnessFactor", label),
        0.f, 1.f);
    if (!(std::max({m.sheen_color[0], m.sheen_color[1], m.sheen_color[2]}) > 0.f)) return;
    m.sheen_color_tex = extension_texture(g, ext, "sheenColorTexture", label, true);
    m.sheen_roughness_tex = extension_texture(g, ext, "sheenRoughnessTexture", label, false);
}

// KHR_materials_iridescence: iridescenceFactor times iridescenceTexture's R weighs a thin film of
// index iridescenceIor (default 1.3) and thickness between iridescenceThicknessMinimum and
// -Maximum (100 and 400 nm) by iridescenceThicknessTexture's G, the maximum without one
// (kernels/iridescence.cl).
void MaterialConverter::convert_iridescence(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    m.iridescence_tex = m.iridescence_thickness_tex = -1;
    m.iridescence_ior = 1.3f;
    m.iridescence_thickness[0] = 100.f;
    m.iridescence_thickness[1] = 400.f;
    auto it = g.extensions.find("KHR_materials_iridescence");
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const char* ext = "KHR_materials_iridescence";
    m.iridescence = std::clamp(
        finite_factor(extension_number(g.extensions, ext, "iridescenceFactor", 0.0), "iridescenceFactor", label), 0.f,
        1.f);
    m.iridescence_ior =
        finite_factor(extension_number(g.extensions, ext, "iridescenceIor", 1.3), "iridescenceIor", label);
    if (m.iridescence_ior < 1.f) {
        ctx_.warn(label + " iridescenceIor " + std::to_string(m.iridescence_ior) + " is below 1; using 1");
        m.iridescence_ior = 1.f;
    }
    for (int k = 0; k < 2; ++k) {
        const char* key = k == 0 ? "iridescenceThicknessMinimum" : "iridescenceThicknessMaximum";
        m.iridescence_thickness[k] =
            finite_factor(extension_number(g.extensions, ext, key, k == 0 ? 100.0 : 400.0), key, label);
        if (m.iridescence_thickness[k] < 0.f) ctx_.fail(label + " " + key + " must be at least 0");
    }
    if (!(m.iridescence > 0.f)) return;
    m.iridescence_tex = extension_texture(g, ext, "iridescenceTexture", label, false);
    m.iridescence_thickness_tex = extension_texture(g, ext, "iridescenceThicknessTexture", label, false);
}

// KHR_materials_anisotropy: anisotropyStrength times anisotropyTexture's B stretches the GGX lobes
// to alpha_t = alpha + (1 - alpha) strength^2 along the texture's RG direction in the tangent frame
// (default +t), turned by anisotropyRotation (kernels/scene.cl anisotropy_direction).
void MaterialConverter::convert_anisotropy(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    m.anisotropy_tex = -1;
    auto it = g.extensions.find("KHR_materials_anisotropy");
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const char* ext = "KHR_materials_anisotropy";
    m.anisotropy_strength = std::clamp(
        finite_factor(extension_number(g.extensions, ext, "anisotropyStrength", 0.0), "anisotropyStrength", label), 0.f,
        1.f);
    m.anisotropy_rotation =
        finite_factor(extension_number(g.extensions, ext, "anisotropyRotation", 0.0), "anisotropyRotation", label);
    if (!(m.anisotropy_strength > 0.f)) return;
    m.anisotropy_tex = extension_texture(g, ext, "anisotropyTexture", label, false);
}

// KHR_materials_diffuse_transmission: diffuseTransmissionFactor times diffuseTransmissionTexture's A
// turns that part of the dielectric's diffuse lobe to the other side of the surface, with colour
// diffuseTransmissionColorFactor times diffuseTransmissionColorTexture (sRGB). Thin unless
// KHR_materials_volume gives the mesh a thickness, whose absorption then applies inside
// (kernels/bsdf.cl).
void MaterialConverter::convert_diffuse_transmission(const tinygltf::Material& g, const std::string& label,
                                                     dev::Material& m) {
    m.diffuse_transmission = 0.f;
    m.diffuse_transmission_tex = m.diffuse_transmission_color_tex = -1;
    for (int c = 0; c < 3; ++c) m.diffuse_transmission_color[c] = 1.f;
    const char* ext = "KHR_materials_diffuse_transmission";
    auto it = g.extensions.find(ext);
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const tinygltf::Value& v = it->second;
    m.diffuse_transmission =
        std::clamp(finite_factor(extension_number(g.extensions, ext, "diffuseTransmissionFactor", 0.0),
                                 "diffuseTransmissionFactor", label),
                   0.f, 1.f);
    if (v.Has("diffuseTransmissionColorFactor")) {
        const tinygltf::Value& c = v.Get("diffuseTransmissionColorFactor");
        if (!c.IsArray() || c.ArrayLen() != 3)
            ctx_.fail(label + " diffuseTransmissionColorFactor must have 3 components");
        for (int k = 0; k < 3; ++k) {
            if (!c.Get(k).IsNumber()) ctx_.fail(label + " diffuseTransmissionColorFactor must have 3 numbers");
            m.diffuse_transmission_color[k] = std::clamp(
                finite_factor(c.Get(k).GetNumberAsDouble(), "diffuseTransmissionColorFactor", label), 0.f, 1.f);
        }
    }
    if (!(m.diffuse_transmission > 0.f)) return;
    m.diffuse_transmission_tex = extension_texture(g, ext, "diffuseTransmissionTexture", label, false);
    m.diffuse_transmission_color_tex = extension_texture(g, ext, "diffuseTransmissionColorTexture", label, true);
}

// KHR_materials_dispersion: dispersion = 20 / V_d (V_d the Abbe number) spreads the index of
// refraction over the wavelength (kernels/dispersion.cl). The extension builds on
// KHR_materials_volume: a thin-walled or opaque material does not bend light, and keeps its one
// index (a note says so when the file asks for dispersion there).
void MaterialConverter::convert_dispersion(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    m.dispersion = 0.f;
    const char* ext = "KHR_materials_dispersion";
    if (!g.extensions.count(ext)) return;
    const float d = finite_factor(extension_number(g.extensions, ext, "dispersion", 0.0), "dispersion", label);
    if (d < 0.f) ctx_.fail(label + " KHR_materials_dispersion dispersion must be at least 0");
    if (!(d > 0.f)) return;
    if (!(m.transmission > 0.f) || (m.flags & MATERIAL_FLAG_THIN_WALLED)) {
        ctx_.warn(label + " KHR_materials_dispersion has no effect without transmission through a volume "
                          "(KHR_materials_volume thicknessFactor > 0)");
        return;
    }
    m.dispersion = d;
}

// A textureInfo inside a material extension (tinygltf leaves those as JSON values): -1 without it.
int32_t MaterialConverter::extension_texture(const tinygltf::Material& g, const char* extension, const char* key,
                                             const std::string& label, bool srgb) {
    auto it = g.extensions.find(extension);
    if (it == g.extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return -1;
    const tinygltf::Value& ti = it->second.Get(key);
    if (!ti.IsObject() || !ti.Has("index") || !ti.Get("index").IsInt())
        ctx_.fail(label + " " + key + " has no texture index");
    int tex_coord = ti.Has("texCoord") && ti.Get("texCoord").IsInt() ? ti.Get("texCoord").GetNumberAsInt() : 0;
    tinygltf::ExtensionMap ext;
    if (ti.Has("extensions") && ti.Get("extensions").IsObject() && ti.Get("extensions").Has("KHR_texture_transform"))
        ext["KHR_texture_transform"] = ti.Get("extensions").Get("KHR_texture_transform");
    return texture_reference(ti.Get("index").GetNumberAsInt(), tex_coord, ext, label, key, srgb);
}

// KHR_materials_transmission's transmissionTexture (R scales transmissionFactor) and
// KHR_materials_volume: inside a mesh whose thicknessFactor is above 0, light is absorbed by
// Beer-Lambert's law with sigma = -ln(attenuationColor) / attenuationDistance per channel
// (kernels/scene.cl volume_transmittance). thicknessTexture only approximates the geometry's
// thickness for rasterisers: a path tracer measures the real one, so it is not read. With
// thicknessFactor 0, or without the extension, the material is thin-walled (the extension's
// definition): nothing is absorbed and transmitted light is not bent (kernels/bsdf.cl).
void MaterialConverter::convert_volume(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    m.transmission_tex = extension_texture(g, "KHR_materials_transmission", "transmissionTexture", label, false);
    for (int c = 0; c < 4; ++c) m.attenuation[c] = 0.f;
    auto it = g.extensions.find("KHR_materials_volume");
    const bool has_volume = it != g.extensions.end() && it->second.IsObject();
    const double thickness =
        has_volume ? extension_number(g.extensions, "KHR_materials_volume", "thicknessFactor", 0.0) : 0.0;
    if (m.transmission > 0.f && !(thickness > 0.0)) m.flags |= MATERIAL_FLAG_THIN_WALLED;
    if (!has_volume) return;
    if (thickness > 0.0) m.flags |= MATERIAL_FLAG_ENCLOSES_VOLUME;
    const tinygltf::Value& v = it->second;
    double distance = extension_number(g.extensions, "KHR_materials_volume", "attenuationDistance", INFINITY);
    if (!(distance > 0.0)) ctx_.fail(label + " KHR_materials_volume attenuationDistance must be positive");
    double color[3] = {1, 1, 1};
    if (v.Has("attenuationColor")) {
        const tinygltf::Value& c = v.Get("attenuationColor");
        if (!c.IsArray() || c.ArrayLen() != 3) ctx_.fail(label + " attenuationColor must have 3 components");
        for (int k = 0; k < 3; ++k) {
            if (!c.Get(k).IsNumber()) ctx_.fail(label + " attenuationColor must have 3 numbers");
            color[k] = std::clamp(c.Get(k).GetNumberAsDouble(), 0.0, 1.0);
        }
    }
    if (!(thickness > 0.0) || std::isinf(distance)) return;
    for (int k = 0; k < 3; ++k) {
        // A colour of 0 absorbs everything: the largest coefficient a float holds.
        const double sigma = color[k] > 0 ? -std::log(color[k]) / distance : 3e38;
        m.attenuation[k] = finite_factor(std::min(sigma, 3e38), "volume attenuation", label);
    }
}

// KHR_materials_volume_scatter (the Khronos draft, as ScatteringSkull uses it): the volume of
// KHR_materials_volume scatters. Its attenuation is the extinction sigma_t, of which the
// single-scattering albedo rho_ss scatters and the rest is absorbed; rho_ss comes from
// multiscatterColor rho_ms, the albedo the medium shows after many scatterings, by the draft's
// inversion (the Khronos sample viewer's multiToSingleScatter): s = 4.09712 + 4.20863 rho_ms -
// sqrt(9.59217 + 41.6808 rho_ms + 17.7126 rho_ms^2), rho_ss = 1 - s^2. scatterAnisotropy is the
// Henyey-Greenstein g.
void MaterialConverter::convert_volume_scatter(const tinygltf::Material& g, const std::string& label,
                                               dev::Material& m) {
    for (float& x : m.scatter) x = 0.f;
    const char* ext = "KHR_materials_volume_scatter";
    auto it = g.extensions.find(ext);
    if (it == g.extensions.end()) return;
    if (!it->second.IsObject()) ctx_.fail(label + " " + ext + " must be an object");
    double rho_ms[3] = {0, 0, 0};
    const tinygltf::Value& v = it->second;
    if (v.Has("multiscatterColor")) {
        const tinygltf::Value& c = v.Get("multiscatterColor");
        if (!c.IsArray() || c.ArrayLen() != 3) ctx_.fail(label + " multiscatterColor must have 3 components");
        for (int k = 0; k < 3; ++k) {
            if (!c.Get(k).IsNumber()) ctx_.fail(label + " multiscatterColor must have 3 numbers");
            rho_ms[k] = std::clamp(c.Get(k).GetNumberAsDouble(), 0.0, 1.0);
        }
    }
    const double aniso = extension_number(g.extensions, ext, "scatterAnisotropy", 0.0);
    if (!(aniso > -1.0 && aniso < 1.0)) ctx_.fail(label + " scatterAnisotropy must be above -1 and below 1");
    if (!(m.flags & MATERIAL_FLAG_ENCLOSES_VOLUME) ||
        !(m.attenuation[0] > 0.f || m.attenuation[1] > 0.f || m.attenuation[2] > 0.f)) {
        ctx_.warn(label + " " + ext +
                  " has no effect without a volume that attenuates (KHR_materials_volume "
                  "thicknessFactor > 0 and a finite attenuationDistance, on a transmitting material)");
        return;
    }
    for (int k = 0; k < 3; ++k) {
        const double r = rho_ms[k];
        const double s = 4.09712 + 4.20863 * r - std::sqrt(9.59217 + 41.6808 * r + 17.7126 * r * r);
        m.scatter[k] = float(std::clamp(1.0 - s * s, 0.0, 1.0));
    }
    m.scatter[3] = float(aniso);
}

// alphaMode (glTF 2.0 Sec. 3.9.4; kernels/alpha.cl): OPAQUE ignores alpha, MASK cuts out where
// alpha < alphaCutoff (default 0.5), BLEND makes the surface that transparent, stochastically.
void MaterialConverter::convert_alpha(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    m.alpha_cutoff = finite_factor(g.alphaCutoff, "alphaCutoff", label);
    if (g.alphaMode == "MASK") m.alpha_mode = ALPHA_MASK;
    else if (g.alphaMode == "BLEND") m.alpha_mode = ALPHA_BLEND;
    else if (g.alphaMode == "OPAQUE" || g.alphaMode.empty()) m.alpha_mode = ALPHA_OPAQUE;
    else ctx_.fail(label + " alphaMode '" + printable(g.alphaMode) + "' is not OPAQUE, MASK or BLEND");
}

// KHR_materials_specular: specularFactor (default 1) scales the dielectric layer's F0 and F90,
// specularColorFactor (default 1) its F0 (kernels/surface_bsdf.cl).
void MaterialConverter::convert_specular(const tinygltf::Material& g, const std::string& label, dev::Material& m) {
    for (int c = 0; c < 3; ++c) m.specular_color[c] = 1.f;
    m.specular_color[3] = 1.f;
    m.specular_tex = m.specular_color_tex = -1;
    auto it = g.extensions.find("KHR_materials_specular");
    if (it == g.extensions.end() || !it->second.IsObject()) return;
    const tinygltf::Value& ext = it->second;
    m.specular_color[3] =
        std::max(0.f, finite_factor(extension_number(g.extensions, "KHR_materials_specular", "specularFactor", 1.0),
                                    "specularFactor", label));
    if (ext.Has("specularColorFactor")) {
        const tinygltf::Value& v = ext.Get("specularColorFactor");
        if (!v.IsArray() || v.ArrayLen() != 3) ctx_.fail(label + " specularColorFactor must have 3 components");
        for (int c = 0; c < 3; ++c) {
            const tinygltf::Value& x = v.Get(c);
            if (!x.IsNumber()) ctx_.fail(label + " specularColorFactor must have 3 numbers");
            m.specular_color[c] = std::max(0.f, finite_factor(x.GetNumberAsDouble(), "specularColorFactor", label));
        }
    }
    if (m.specular_color[3] > 1.f) {
        ctx_.warn(label + " specularFactor " + std::to_string(m.specular_color[3]) + " is above 1; using 1");
        m.specular_color[3] = 1.f;
    }
    // specularTexture's A scales specularFactor, specularColorTexture (sRGB) the colour factor.
    m.specular_tex = extension_texture(g, "KHR_materials_specular", "specularTexture", label, false);
    m.specular_color_tex = extension_texture(g, "KHR_materials_specular", "specularColorTexture", label, true);
}

uint32_t MaterialConverter::material_index(int gltf_material, const std::string& owner) {
    if (gltf_material >= 0 && size_t(gltf_material) < m_.materials.size()) return uint32_t(gltf_material);
    if (gltf_material >= 0) ctx_.fail(owner + " material " + std::to_string(gltf_material) + " out of range");
    if (default_material_ < 0) {
        default_material_ = int(s_.materials.size());
        s_.materials.push_back(default_material());
    }
    return uint32_t(default_material_);
}

} // namespace clppm::gltf
