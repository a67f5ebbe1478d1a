#include "scene/material_defaults.h"

namespace clppm {

dev::Material default_material() {
    dev::Material m{};
    for (int c = 0; c < 3; ++c) m.base_color[c] = 1.f;
    m.base_color[3] = 1.f;
    m.metallic = 1.f;
    m.roughness = 1.f;
    m.ior = 1.5f;
    for (int c = 0; c < 4; ++c) m.specular_color[c] = 1.f;
    m.base_color_tex = -1;
    m.metallic_roughness_tex = -1;
    m.emissive_tex = -1;
    m.normal_tex = -1;
    m.normal_scale = 1.f;
    m.alpha_mode = ALPHA_OPAQUE;
    m.alpha_cutoff = 0.5f;
    m.transmission_tex = -1;
    m.specular_tex = m.specular_color_tex = -1;
    m.clearcoat_tex = m.clearcoat_roughness_tex = m.clearcoat_normal_tex = -1;
    m.clearcoat_normal_scale = 1.f;
    m.sheen_color_tex = m.sheen_roughness_tex = -1;
    m.iridescence_tex = m.iridescence_thickness_tex = -1;
    m.anisotropy_tex = -1;
    m.diffuse_transmission_tex = m.diffuse_transmission_color_tex = -1;
    for (int c = 0; c < 3; ++c) m.diffuse_transmission_color[c] = 1.f;
    return m;
}

} // namespace clppm
