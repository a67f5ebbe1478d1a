// EXT_mesh_gpu_instancing, the SceneBuilder's part for it (scene/gltf/gltf_scene_builder.h): the
// instances' transforms from the node's TRANSLATION, ROTATION and SCALE accessors.
#include "scene/gltf/gltf_scene_builder.h"

#include <algorithm>
#include <cmath>

#include "scene/gltf/gltf_skin.h"
#include "scene/gltf/gltf_tangents.h"
#include "scene/gltf/gltf_transform.h"

namespace clppm::gltf {

// EXT_mesh_gpu_instancing: the node's mesh is drawn once per element of its TRANSLATION,
// ROTATION and SCALE accessors (each optional, all of one count), at node world * T * R * S.
const tinygltf::Value* SceneBuilder::instancing_attributes(const tinygltf::Node& node, const std::string& label) {
    auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
    if (ext == node.extensions.end()) return nullptr;
    if (!ext->second.IsObject() || !ext->second.Has("attributes") || !ext->second.Get("attributes").IsObject())
        ctx_.fail(label + " EXT_mesh_gpu_instancing has no attributes object");
    return &ext->second.Get("attributes");
}

int SceneBuilder::instancing_accessor(const tinygltf::Value& attributes, const char* name, const std::string& label) {
    if (!attributes.Has(name)) return -1;
    const tinygltf::Value& v = attributes.Get(name);
    if (!v.IsInt() || v.GetNumberAsInt() < 0)
        ctx_.fail(label + " EXT_mesh_gpu_instancing " + name + " is not an accessor index");
    return v.GetNumberAsInt();
}

// 0: the node is not instanced (drawn once).
size_t SceneBuilder::gpu_instance_count(const tinygltf::Node& node, const std::string& label) {
    const tinygltf::Value* attributes = instancing_attributes(node, label);
    if (!attributes) return 1;
    size_t count = 0;
    bool any = false;
    for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"}) {
        int a = instancing_accessor(*attributes, name, label);
        if (a < 0) continue;
        size_t n = reader_.view(a, label + " EXT_mesh_gpu_instancing " + name).count;
        if (any && n != count)
            ctx_.fail(label + " EXT_mesh_gpu_instancing attributes have different counts (" + std::to_string(count) +
                      " and " + std::to_string(n) + ")");
        count = n, any = true;
    }
    return any ? count : 1;
}

std::vector<glm::dmat4> SceneBuilder::gpu_instances(const tinygltf::Node& node, const std::string& label) {
    const tinygltf::Value* attributes = instancing_attributes(node, label);
    if (!attributes) return {};
    size_t count = gpu_instance_count(node, label);
    std::string what = label + " EXT_mesh_gpu_instancing ";
    auto read = [&](const char* name, int components, bool rotation) {
        int a = instancing_accessor(*attributes, name, label);
        if (a < 0) return AccessorView{};
        AccessorView v = reader_.view(a, what + name);
        bool ok =
            v.components == components &&
            (v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
             (rotation && v.normalized &&
              (v.component_type == TINYGLTF_COMPONENT_TYPE_BYTE || v.component_type == TINYGLTF_COMPONENT_TYPE_SHORT)));
        require(ok, what + name +
                        (rotation ? " must be a VEC4 of FLOAT or normalized BYTE/SHORT" : " must be a FLOAT VEC3"));
        return v;
    };
    AccessorView t = read("TRANSLATION", 3, false), r = read("ROTATION", 4, true), s = read("SCALE", 3, false);
    std::vector<glm::dmat4> m(count);
    for (size_t i = 0; i < count; ++i) {
        glm::dvec3 ti = t.data ? glm::dvec3(t.get(i, 0), t.get(i, 1), t.get(i, 2)) : glm::dvec3(0.0);
        glm::dvec3 si = s.data ? glm::dvec3(s.get(i, 0), s.get(i, 1), s.get(i, 2)) : glm::dvec3(1.0);
        std::vector<double> qi = {0, 0, 0, 1};
        if (r.data) qi = {r.get(i, 0), r.get(i, 1), r.get(i, 2), r.get(i, 3)};
        m[i] = trs_matrix(ti, qi, si);
    }
    return m;
}

} // namespace clppm::gltf
