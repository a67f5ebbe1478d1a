// KHR_lights_punctual lights and perspective cameras of the node hierarchy -> dev::Light and
// CameraDesc in world space.
#pragma once
#include <cstdint>
#include <string>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

class LightsAndCameras {
public:
    LightsAndCameras(const tinygltf::Model& m, LoadContext& ctx, Scene& s) : m_(m), ctx_(ctx), s_(s) {}

    // The light a node's KHR_lights_punctual extension `ext` names, placed by `world`.
    void add_light(const tinygltf::Value& ext, const glm::dmat4& world, const std::string& node_label);
    // The node's camera, placed by `world`; non-perspective cameras are skipped with a warning.
    void add_camera(const tinygltf::Node& node, const glm::dmat4& world, const std::string& node_label);

private:
    static bool light_type(const std::string& type, uint32_t* out);

    void set_light_radiance(const tinygltf::Light& g, const std::string& label, dev::Light* l);

    void set_spot_cone(const tinygltf::Light& g, const std::string& label, dev::Light* l);

    // Thin-lens parameters from the camera's extras, else its node's; 0 when absent.
    float camera_extra(const tinygltf::Camera& cam, const tinygltf::Node& node, const char* key,
                       const std::string& label);

    const tinygltf::Model& m_;
    LoadContext& ctx_;
    Scene& s_;
};

} // namespace clppm::gltf
