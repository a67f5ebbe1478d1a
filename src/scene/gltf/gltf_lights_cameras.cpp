#include "scene/gltf/gltf_lights_cameras.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/gltf/gltf_transform.h"
#include "scene/light_power.h"

namespace clppm::gltf {

void LightsAndCameras::add_light(const tinygltf::Value& ext, const glm::dmat4& world, const std::string& node_label) {
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt())
        ctx_.fail(node_label + " KHR_lights_punctual has no light index");
    int index = ext.Get("light").GetNumberAsInt();
    if (index < 0 || size_t(index) >= m_.lights.size())
        ctx_.fail(node_label + " light " + std::to_string(index) + " out of range (" +
                  std::to_string(m_.lights.size()) + " lights)");
    const tinygltf::Light& g = m_.lights[size_t(index)];
    std::string label = labelled("light", index, g.name);
    dev::Light l{};
    if (!light_type(g.type, &l.type)) {
        ctx_.warn(label + " type '" + g.type + "' is not supported; skipped");
        return;
    }
    if (g.range > 0.0) ctx_.warn("KHR_lights_punctual range is ignored (lights reach infinitely far)");
    set_light_radiance(g, label, &l);
    glm::dvec3 dir = unit_or_zero(transform_dir(world, {0, 0, -1}));
    if (dir == glm::dvec3(0.0) && l.type != LIGHT_POINT) {
        ctx_.warn(node_label + " transform collapses the direction of " + label + "; skipped");
        return;
    }
    store3(l.position, transform_point(world, {0, 0, 0}));
    l.position[3] = 1.f;
    if (!std::isfinite(l.position[0]) || !std::isfinite(l.position[1]) || !std::isfinite(l.position[2]))
        ctx_.fail(node_label + " places " + label + " outside the float range");
    store3(l.direction, dir);
    set_spot_cone(g, label, &l);
    // The renderer weights the lights (scene/light_power.h); one too bright for a float is
    // refused here, with the file's name for it. Directional power needs the scene's size.
    if (!std::isfinite(narrow_to_float(punctual_light_power(l, 0.0))))
        ctx_.fail(label + " has a non-finite power (intensity too large)");
    s_.punctual_lights.push_back(l);
}

bool LightsAndCameras::light_type(const std::string& type, uint32_t* out) {
    if (type == "point") return *out = LIGHT_POINT, true;
    if (type == "spot") return *out = LIGHT_SPOT, true;
    if (type == "directional") return *out = LIGHT_DIRECTIONAL, true;
    return false;
}

void LightsAndCameras::set_light_radiance(const tinygltf::Light& g, const std::string& label, dev::Light* l) {
    std::vector<double> color = g.color.empty() ? std::vector<double>{1.0, 1.0, 1.0} : g.color;
    if (color.size() != 3) ctx_.fail(label + " color must have 3 components");
    for (int c = 0; c < 3; ++c) {
        l->radiance[c] = narrow_to_float(color[size_t(c)] * g.intensity);
        if (!std::isfinite(l->radiance[c])) ctx_.fail(label + " has a non-finite color or intensity");
        if (l->radiance[c] < 0.f) ctx_.fail(label + " has a negative color or intensity");
    }
}

void LightsAndCameras::set_spot_cone(const tinygltf::Light& g, const std::string& label, dev::Light* l) {
    if (l->type != LIGHT_SPOT) return;
    double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
    if (!std::isfinite(inner) || !std::isfinite(outer)) ctx_.fail(label + " has non-finite cone angles");
    double outer_c = std::clamp(outer, 1e-6, kPi / 2), inner_c = std::clamp(inner, 0.0, outer_c);
    if (outer_c != outer || inner_c != inner) ctx_.warn(label + " cone angles clamped to 0 <= inner <= outer <= pi/2");
    l->cos_inner = float(std::cos(inner_c));
    l->cos_outer = float(std::cos(outer_c));
}
void LightsAndCameras::add_camera(const tinygltf::Node& node, const glm::dmat4& world, const std::string& node_label) {
    if (size_t(node.camera) >= m_.cameras.size())
        ctx_.fail(node_label + " camera " + std::to_string(node.camera) + " out of range");
    const tinygltf::Camera& g = m_.cameras[size_t(node.camera)];
    std::string label = labelled("camera", node.camera, g.name);
    if (g.type != "perspective" && g.type != "orthographic") {
        ctx_.warn(label + " type '" + printable(g.type) + "' is neither perspective nor orthographic; skipped");
        return;
    }
    glm::dvec3 forward = unit_or_zero(transform_dir(world, {0, 0, -1}));
    glm::dvec3 up = transform_dir(world, {0, 1, 0});
    up = unit_or_zero(up - glm::dot(up, forward) * forward); // Gram-Schmidt
    if (forward == glm::dvec3(0.0) || up == glm::dvec3(0.0)) {
        ctx_.warn(node_label + " transform collapses " + label + "; skipped");
        return;
    }
    CameraDesc c;
    c.name = g.name.empty() ? node.name : g.name;
    store3(c.position, transform_point(world, {0, 0, 0}));
    if (!std::isfinite(c.position[0]) || !std::isfinite(c.position[1]) || !std::isfinite(c.position[2]))
        ctx_.fail(node_label + " places " + label + " outside the float range");
    store3(c.forward, forward);
    store3(c.up, up);
    if (g.type == "orthographic") {
        // xmag and ymag: half the view's width and height (glTF 2.0 Sec. 3.10.3), as given; the
        // node's scale, like a perspective camera's, does not change the view. A sign mirrors
        // nothing here.
        c.orthographic = true;
        c.xmag = narrow_to_float(std::fabs(g.orthographic.xmag));
        c.ymag = narrow_to_float(std::fabs(g.orthographic.ymag));
        if (!(c.xmag > 0.f && std::isfinite(c.xmag) && c.ymag > 0.f && std::isfinite(c.ymag)))
            ctx_.fail(label + " xmag and ymag must be finite and not 0");
        c.aspect = c.xmag / c.ymag;
        c.znear = narrow_to_float(g.orthographic.znear);
        if (!(c.znear >= 0.f && std::isfinite(c.znear))) ctx_.fail(label + " znear must be a number >= 0");
        if (camera_extra(g, node, "aperture_radius", label) > 0.f)
            ctx_.warn(label + " is orthographic; its extras.aperture_radius (a thin lens) is ignored");
        s_.cameras.push_back(c);
        return;
    }
    c.yfov = narrow_to_float(g.perspective.yfov);
    if (!(c.yfov > 0.f && c.yfov < float(kPi))) ctx_.fail(label + " yfov must lie in (0, pi)");
    c.aspect = narrow_to_float(g.perspective.aspectRatio);
    if (!std::isfinite(c.aspect) || c.aspect < 0.f) ctx_.fail(label + " has an invalid aspectRatio");
    c.znear = narrow_to_float(g.perspective.znear);
    if (!(c.znear >= 0.f && std::isfinite(c.znear))) ctx_.fail(label + " znear must be a number >= 0");
    c.aperture_radius = camera_extra(g, node, "aperture_radius", label);
    c.focus_distance = camera_extra(g, node, "focus_distance", label);
    s_.cameras.push_back(c);
}

// Thin-lens parameters from the camera's extras, else its node's; 0 when absent.
float LightsAndCameras::camera_extra(const tinygltf::Camera& cam, const tinygltf::Node& node, const char* key,
                                     const std::string& label) {
    for (const tinygltf::Value* extras : {&cam.extras, &node.extras}) {
        if (!extras->IsObject() || !extras->Has(key)) continue;
        const tinygltf::Value& v = extras->Get(key);
        float f = v.IsNumber() ? narrow_to_float(v.GetNumberAsDouble()) : -1.f;
        if (!std::isfinite(f) || f < 0.f) ctx_.fail(label + " extras." + key + " must be a number >= 0");
        return f;
    }
    return 0.f;
}
} // namespace clppm::gltf
