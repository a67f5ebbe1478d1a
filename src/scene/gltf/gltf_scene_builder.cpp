#include "scene/gltf/gltf_scene_builder.h"

#include <algorithm>
#include <cmath>

#include "scene/gltf/gltf_skin.h"
#include "scene/gltf/gltf_tangents.h"
#include "scene/gltf/gltf_transform.h"

namespace clppm::gltf {

namespace {
// A material whose shading reads tangents: a normal map, a clearcoat's own, or anisotropy.
bool normal_mapped(const dev::Material& m) {
    return m.normal_tex >= 0 || (m.clearcoat > 0.f && m.clearcoat_normal_tex >= 0) || m.anisotropy_strength > 0.f;
}
} // namespace

void SceneBuilder::build() {
    warn_unsupported_extensions();
    materials_.convert_materials();
    for (const dev::Material& m : s_.materials) tangents_needed_ = tangents_needed_ || normal_mapped(m);
    for (const tinygltf::Mesh& mesh : m_.meshes)
        for (const tinygltf::Primitive& prim : mesh.primitives)
            colors_needed_ = colors_needed_ || prim.attributes.count("COLOR_0");
    std::vector<int> roots = root_nodes();
    // Instancing multiplies triangles: a few kilobytes of nodes can name 2^26 of them. A first
    // pass that only counts makes such a file fail before it fills gigabytes.
    counting_ = true;
    traverse(roots);
    counting_ = false;
    visits_ = 0;
    traverse(roots);
    if (s_.shading.empty()) ctx_.fail("no triangle geometry");
}

void SceneBuilder::warn_unsupported_extensions() {
    for (const std::string& name : m_.extensionsUsed)
        if (!kSupportedExtensions.count(name)) ctx_.warn("extension " + name + " is not supported; ignored");
}

std::vector<int> SceneBuilder::root_nodes() {
    if (m_.scenes.empty()) return parentless_nodes();
    int scene = m_.defaultScene >= 0 ? m_.defaultScene : 0;
    if (size_t(scene) >= m_.scenes.size())
        ctx_.fail("default scene " + std::to_string(scene) + " out of range (" + std::to_string(m_.scenes.size()) +
                  " scenes)");
    return m_.scenes[size_t(scene)].nodes;
}

// Without a `scenes` array, render every node that is nobody's child.
std::vector<int> SceneBuilder::parentless_nodes() {
    std::vector<char> is_child(m_.nodes.size(), 0);
    for (const auto& n : m_.nodes)
        for (int c : n.children)
            if (c >= 0 && size_t(c) < m_.nodes.size()) is_child[size_t(c)] = 1;
    std::vector<int> roots;
    for (size_t i = 0; i < m_.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(int(i));
    return roots;
}

struct SceneBuilder::Frame {
    int node;
    glm::dmat4 world;
    size_t next_child;
};

// Depth-first with an explicit stack (no recursion limit on deep chains); a node already on
// the current path is its own ancestor: a cycle.
void SceneBuilder::traverse(const std::vector<int>& roots) {
    on_path_.assign(m_.nodes.size(), 0);
    for (int root : roots) {
        std::vector<Frame> stack;
        enter(root, glm::dmat4(1.0), -1, stack);
        while (!stack.empty()) {
            Frame& top = stack.back();
            const std::vector<int>& children = m_.nodes[size_t(top.node)].children;
            if (top.next_child == children.size()) {
                on_path_[size_t(top.node)] = 0;
                stack.pop_back();
                continue;
            }
            int child = children[top.next_child++];
            glm::dmat4 parent = top.world; // copied: push_back may move `top`
            enter(child, parent, top.node, stack);
        }
    }
}

// Labels are built only on the way to an error: shared subtrees make this path hot.
void SceneBuilder::enter(int index, const glm::dmat4& parent, int parent_index, std::vector<Frame>& stack) {
    if (index < 0 || size_t(index) >= m_.nodes.size())
        ctx_.fail((parent_index < 0 ? std::string("scene root") : node_label(parent_index) + " child") + " node " +
                  std::to_string(index) + " out of range (" + std::to_string(m_.nodes.size()) + " nodes)");
    const tinygltf::Node& node = m_.nodes[size_t(index)];
    if (on_path_[size_t(index)]) ctx_.fail("node graph cycle: " + node_label(index) + " is its own ancestor");
    if (++visits_ > kMaxNodeVisits) ctx_.fail("the node hierarchy instances more than 2^20 nodes");
    glm::dmat4 world(1.0); // the counting pass needs no transforms
    if (counting_) {
        size_t instances = node.mesh == -1 ? 1 : gpu_instance_count(node, node_label(index));
        if (instances > 1) visits_ += instances - 1;
        if (visits_ > kMaxNodeVisits) ctx_.fail("the node hierarchy instances more than 2^20 nodes");
        for (size_t i = 0; i < instances; ++i) count_triangles(node.mesh);
    } else {
        if (!transform_arrays_valid(node)) ctx_.fail(node_label(index) + " has a transform array of the wrong length");
        glm::dmat4 local = local_matrix(node);
        world = parent * local;
        if (!finite(local) || !finite(world)) ctx_.fail(node_label(index) + " has a non-finite transform");
        instantiate(index, world);
    }
    on_path_[size_t(index)] = 1;
    stack.push_back({index, world, 0});
}

void SceneBuilder::instantiate(int index, const glm::dmat4& world) {
    const tinygltf::Node& node = m_.nodes[size_t(index)];
    auto light = node.extensions.find("KHR_lights_punctual");
    bool has_light = light != node.extensions.end();
    if (node.mesh == -1 && node.camera == -1 && !has_light) return;
    std::string label = node_label(index);
    if (node.mesh != -1 && node.skin >= 0) {
        // Skinned (gltf_skin.h): the joints place the vertices, the node's own transform does not.
        auto j = joints_.find(node.skin);
        if (j == joints_.end())
            j = joints_.emplace(node.skin, joint_matrices(m_, reader_, ctx_, node.skin, label)).first;
        skin_ = &j->second;
        add_mesh(node.mesh, glm::dmat4(1.0), label);
        skin_ = nullptr;
    } else if (node.mesh != -1) {
        std::vector<glm::dmat4> instances = gpu_instances(node, label);
        if (instances.empty()) add_mesh(node.mesh, world, label);
        for (size_t i = 0; i < instances.size(); ++i) {
            glm::dmat4 w = world * instances[i];
            if (!finite(w))
                ctx_.fail(label + " EXT_mesh_gpu_instancing instance " + std::to_string(i) +
                          " has a non-finite transform");
            add_mesh(node.mesh, w, label);
        }
    }
    if (node.camera != -1) lights_cameras_.add_camera(node, world, label);
    if (has_light) lights_cameras_.add_light(light->second, world, label);
}

// Adds the triangles an instance of `mesh` will add (an upper bound: degenerate ones count).
void SceneBuilder::count_triangles(int mesh) {
    if (mesh < 0 || size_t(mesh) >= m_.meshes.size()) return; // add_mesh reports it
    auto cached = mesh_triangles_.find(mesh);
    if (cached == mesh_triangles_.end()) {
        size_t n = 0; // each count <= 2^31 (AccessorReader)
        const tinygltf::Mesh& g = m_.meshes[size_t(mesh)];
        for (size_t p = 0; p < g.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = g.primitives[p];
            if (!is_triangle_mode(prim.mode) || !prim.attributes.count("POSITION")) continue;
            std::string label = labelled("mesh", mesh, g.name) + " primitive " + std::to_string(p);
            size_t vertices = attribute(prim, "POSITION", label).count;
            n += triangle_count(prim.mode,
                                prim.indices < 0 ? vertices : reader_.view(prim.indices, label + " indices").count);
        }
        cached = mesh_triangles_.emplace(mesh, n).first;
    }
    instanced_triangles_ += cached->second;
    if (instanced_triangles_ > kMaxTriangles) ctx_.fail("the scene has more than 2^25 triangles");
}

void SceneBuilder::add_mesh(int mesh, const glm::dmat4& world, const std::string& node_label) {
    if (size_t(mesh) >= m_.meshes.size()) ctx_.fail(node_label + " mesh " + std::to_string(mesh) + " out of range");
    const tinygltf::Mesh& g = m_.meshes[size_t(mesh)];
    for (size_t p = 0; p < g.primitives.size(); ++p) {
        std::string label = labelled("mesh", mesh, g.name) + " primitive " + std::to_string(p);
        const tinygltf::Primitive& prim = g.primitives[p];
        if (!is_triangle_mode(prim.mode)) {
            ctx_.warn(label + ": mode " + std::to_string(prim.mode) + " (" + mode_name(prim.mode) +
                      ") has no area to render; skipped");
            continue;
        }
        if (!prim.attributes.count("POSITION")) {
            ctx_.warn(label + ": no POSITION attribute; skipped");
            continue;
        }
        if (!prim.attributes.count("NORMAL") && meshes_without_normals_.insert(mesh).second)
            ++s_.meshes_without_normals;
        add_primitive(prim, world, label);
    }
}

AccessorView SceneBuilder::attribute(const tinygltf::Primitive& prim, const char* name, const std::string& label) {
    return reader_.view(prim.attributes.at(name), label + " " + name);
}

void SceneBuilder::require(bool ok, const std::string& what) {
    if (!ok) ctx_.fail(what);
}

WorldVertices SceneBuilder::world_vertices(const tinygltf::Primitive& prim, const glm::dmat4& world,
                                           const std::string& label) {
    WorldVertices v;
    AccessorView pos = attribute(prim, "POSITION", label);
    // KHR_mesh_quantization adds (normalized or not) BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT.
    require(pos.components == 3 && pos.component_type != TINYGLTF_COMPONENT_TYPE_INT &&
                pos.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
            label + ": POSITION must be a VEC3 of FLOAT or (KHR_mesh_quantization) BYTE/SHORT, signed or unsigned");
    v.position.resize(pos.count);
    for (size_t i = 0; i < pos.count; ++i)
        v.position[i] = transform_point(world, {pos.get(i, 0), pos.get(i, 1), pos.get(i, 2)});
    if (prim.attributes.count("NORMAL")) read_normals(prim, world, label, &v);
    if (prim.attributes.count("TEXCOORD_0")) read_uvs(prim, label, "TEXCOORD_0", &v.uv, v.position.size());
    if (materials_.uses_texcoord1() && prim.attributes.count("TEXCOORD_1"))
        read_uvs(prim, label, "TEXCOORD_1", &v.uv1, v.position.size());
    if (tangents_needed_ && prim.attributes.count("TANGENT")) read_tangents(prim, world, label, &v);
    if (prim.attributes.count("COLOR_0")) read_colors(prim, label, &v);
    if (skin_) apply_skin(prim, *skin_, reader_, ctx_, label, &v);
    return v;
}

// COLOR_0 (glTF 2.0 Sec. 3.7.2.1): linear RGB or RGBA, FLOAT or normalized UNSIGNED_BYTE/SHORT.
void SceneBuilder::read_colors(const tinygltf::Primitive& prim, const std::string& label, WorldVertices* v) {
    AccessorView c = attribute(prim, "COLOR_0", label);
    bool unorm = c.normalized && (c.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                  c.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    require((c.components == 3 || c.components == 4) && (c.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || unorm),
            label + ": COLOR_0 must be a VEC3 or VEC4 of FLOAT or normalized UNSIGNED_BYTE/SHORT");
    require(c.count >= v->position.size(), label + ": COLOR_0 has fewer elements than POSITION");
    v->color.resize(v->position.size());
    for (size_t i = 0; i < v->color.size(); ++i) {
        glm::vec4 col(1.f);
        for (int k = 0; k < c.components; ++k) {
            float x = narrow_to_float(c.get(i, k));
            col[k] = std::isfinite(x) ? std::clamp(x, 0.f, 1.f) : 1.f;
        }
        v->color[i] = col;
    }
}

void SceneBuilder::read_tangents(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label,
                                 WorldVertices* v) {
    AccessorView t = attribute(prim, "TANGENT", label);
    bool snorm = t.normalized && (t.component_type == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                  t.component_type == TINYGLTF_COMPONENT_TYPE_SHORT);
    require(t.components == 4 && (t.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || snorm),
            label + ": TANGENT must be a VEC4 of FLOAT or (KHR_mesh_quantization) normalized BYTE/SHORT");
    require(t.count >= v->position.size(), label + ": TANGENT has fewer elements than POSITION");
    glm::dmat3 linear(world);
    double mirror = glm::determinant(linear) < 0 ? -1.0 : 1.0;
    v->tangent.resize(v->position.size());
    for (size_t i = 0; i < v->tangent.size(); ++i) {
        glm::dvec3 dir = unit_or_zero(linear * glm::dvec3(t.get(i, 0), t.get(i, 1), t.get(i, 2)));
        v->tangent[i] = glm::dvec4(dir, (t.get(i, 3) < 0 ? -1.0 : 1.0) * mirror);
    }
}

// Normals by the inverse transpose, so they stay perpendicular under non-uniform scale.
void SceneBuilder::read_normals(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label,
                                WorldVertices* v) {
    AccessorView n = attribute(prim, "NORMAL", label);
    bool snorm = n.normalized && (n.component_type == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                  n.component_type == TINYGLTF_COMPONENT_TYPE_SHORT);
    require(n.components == 3 && (n.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || snorm),
            label + ": NORMAL must be a VEC3 of FLOAT or (KHR_mesh_quantization) normalized BYTE/SHORT");
    require(n.count >= v->position.size(), label + ": NORMAL has fewer elements than POSITION");
    glm::dmat3 linear(world);
    double det = glm::determinant(linear);
    glm::dmat3 normal_matrix = std::abs(det) > 1e-300 ? glm::transpose(glm::inverse(linear)) : glm::dmat3(0.0);
    v->normal.resize(v->position.size());
    for (size_t i = 0; i < v->normal.size(); ++i)
        v->normal[i] = unit_or_zero(normal_matrix * glm::dvec3(n.get(i, 0), n.get(i, 1), n.get(i, 2)));
}

void SceneBuilder::read_uvs(const tinygltf::Primitive& prim, const std::string& label, const char* name,
                            std::vector<glm::vec2>* out, size_t vertices) {
    AccessorView t = attribute(prim, name, label);
    // Core glTF: FLOAT or normalized UNSIGNED_BYTE/SHORT; KHR_mesh_quantization adds the signed
    // and the unnormalized 8- and 16-bit integers (scaled by KHR_texture_transform in practice).
    require(t.components == 2 && t.component_type != TINYGLTF_COMPONENT_TYPE_INT &&
                t.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
            label + ": " + name + " must be a VEC2 of FLOAT or 8- or 16-bit integers");
    require(t.count >= vertices, label + ": " + name + " has fewer elements than POSITION");
    out->resize(vertices);
    for (size_t i = 0; i < vertices; ++i) {
        (*out)[i] = {narrow_to_float(t.get(i, 0)), narrow_to_float(t.get(i, 1))};
        if (!std::isfinite((*out)[i].x) || !std::isfinite((*out)[i].y)) (*out)[i] = {0.f, 0.f};
    }
}

bool is_triangle_mode(int mode) {
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

const char* mode_name(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case 3: return "LINE_STRIP";
    default: return "not a glTF primitive mode";
    }
}

size_t triangle_count(int mode, size_t vertices) {
    if (mode == TINYGLTF_MODE_TRIANGLES) return vertices / 3;
    return vertices >= 3 ? vertices - 2 : 0;
}

// Vertex indices of the primitive, three per triangle, as glTF 2.0 Sec. 3.7.2.1 assembles them:
// TRIANGLES (a trailing partial triangle dropped), TRIANGLE_STRIP p_i = {v_i, v_{i+1+i%2},
// v_{i+2-i%2}}, TRIANGLE_FAN p_i = {v_{i+1}, v_{i+2}, v_0}. Strip and fan triangles that repeat a
// vertex (how strips are joined) are dropped as intended, not counted as degenerate.
std::vector<uint32_t> SceneBuilder::triangle_indices(const tinygltf::Primitive& prim, size_t vertex_count,
                                                     const std::string& label) {
    std::vector<uint32_t> v = vertex_sequence(prim, vertex_count, label);
    if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        if (v.size() % 3)
            ctx_.warn(label + (prim.indices < 0 ? ": vertex" : ": index") + " count is not a multiple of 3");
        reserve_triangles(v.size() / 3);
        v.resize(v.size() / 3 * 3);
        return v;
    }
    size_t n = triangle_count(prim.mode, v.size());
    reserve_triangles(n);
    std::vector<uint32_t> idx;
    idx.reserve(3 * n);
    for (size_t i = 0; i < n; ++i) {
        std::array<uint32_t, 3> t = prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP
                                        ? std::array<uint32_t, 3>{v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]}
                                        : std::array<uint32_t, 3>{v[i + 1], v[i + 2], v[0]};
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
        idx.insert(idx.end(), t.begin(), t.end());
    }
    return idx;
}

// The primitive's vertices in drawing order: its indices, else 0, 1, ..., vertex_count - 1.
std::vector<uint32_t> SceneBuilder::vertex_sequence(const tinygltf::Primitive& prim, size_t vertex_count,
                                                    const std::string& label) {
    std::vector<uint32_t> idx;
    if (prim.indices < 0) {
        if (vertex_count > 3 * kMaxTriangles) ctx_.fail("the scene has more than 2^25 triangles");
        idx.resize(vertex_count);
        for (size_t i = 0; i < idx.size(); ++i) idx[i] = uint32_t(i);
        return idx;
    }
    AccessorView a = reader_.view(prim.indices, label + " indices");
    std::string name = "accessor " + std::to_string(prim.indices);
    bool index_type = a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                      a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                      a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    require(a.components == 1 && index_type && !a.normalized,
            label + ": indices " + name + " must be a SCALAR of UNSIGNED_BYTE/SHORT/INT");
    if (a.count > 3 * kMaxTriangles) ctx_.fail("the scene has more than 2^25 triangles");
    idx.resize(a.count);
    for (size_t i = 0; i < idx.size(); ++i) {
        idx[i] = a.index(i);
        if (idx[i] >= vertex_count)
            ctx_.fail("indices " + name + " reference vertex " + std::to_string(idx[i]) + " beyond the " +
                      std::to_string(vertex_count) + " vertices of " + label + " POSITION");
    }
    return idx;
}

void SceneBuilder::reserve_triangles(size_t count) {
    if (count > kMaxTriangles || s_.shading.size() + count > kMaxTriangles)
        ctx_.fail("the scene has more than 2^25 triangles");
}

void SceneBuilder::add_primitive(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label) {
    uint32_t material = materials_.material_index(prim.material, label);
    WorldVertices v = world_vertices(prim, world, label);
    const dev::Material& mat = s_.materials[material];
    bool set[2] = {false, false}; // the coordinate sets the material's textures read
    for (int32_t tex : {mat.base_color_tex, mat.metallic_roughness_tex, mat.emissive_tex, mat.normal_tex})
        if (tex >= 0) set[s_.textures[size_t(tex)].texcoord ? 1 : 0] = true;
    if (v.uv.empty() && set[0])
        ctx_.warn(label + ": textured material without TEXCOORD_0; every texel lookup uses (0, 0)");
    if (v.uv1.empty() && set[1])
        ctx_.warn(label + ": a texture reads TEXCOORD_1, which the primitive lacks; its lookups use (0, 0)");
    std::vector<uint32_t> idx = triangle_indices(prim, v.position.size(), label);
    // Tangents per corner: the file's per vertex, else generated where the material needs them.
    std::vector<glm::dvec4> corner_tangents;
    if (tangents_needed_ && normal_mapped(s_.materials[material])) {
        if (!v.tangent.empty()) {
            corner_tangents.resize(idx.size());
            for (size_t i = 0; i < idx.size(); ++i) corner_tangents[i] = v.tangent[idx[i]];
        } else if (v.uv.empty()) {
            ctx_.warn(label + ": normal-mapped material without TEXCOORD_0; the normal map is ignored");
        } else {
            corner_tangents = generate_tangents(idx, v.position, v.normal, v.uv);
        }
    }
    // A mirroring transform reverses the winding; swapping two vertices restores the
    // counter-clockwise front face that agrees with the (inverse-transpose) normals.
    bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
        std::array<uint32_t, 3> tri = {idx[t], idx[t + 1], idx[t + 2]};
        std::array<glm::dvec4, 3> tangent{};
        if (!corner_tangents.empty()) tangent = {corner_tangents[t], corner_tangents[t + 1], corner_tangents[t + 2]};
        if (mirrored) std::swap(tri[1], tri[2]), std::swap(tangent[1], tangent[2]);
        add_triangle(tri, v, material, corner_tangents.empty() ? nullptr : &tangent);
    }
}

void SceneBuilder::add_triangle(const std::array<uint32_t, 3>& tri, const WorldVertices& v, uint32_t material,
                                const std::array<glm::dvec4, 3>* tangent) {
    Vec3 p[3];
    glm::dvec3 q[3]; // the float positions as stored, for the area test
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3& w = v.position[tri[size_t(k)]];
        p[k] = {narrow_to_float(w.x), narrow_to_float(w.y), narrow_to_float(w.z)};
        q[k] = {p[k].x, p[k].y, p[k].z};
    }
    glm::dvec3 e1 = q[1] - q[0], e2 = q[2] - q[0], c = glm::cross(e1, e2);
    double c2 = glm::dot(c, c);
    // Zero area (or sin(angle) < 1e-7) and non-finite corners give no usable plane.
    if (!finite(q[0]) || !finite(q[1]) || !finite(q[2]) || !(c2 > 1e-14 * glm::dot(e1, e1) * glm::dot(e2, e2))) {
        ++s_.degenerate_triangles_skipped;
        return;
    }
    glm::dvec3 flat = c / std::sqrt(c2);
    dev::TriShading sh{};
    bool smooth = !v.normal.empty();
    for (int k = 0; k < 3 && smooth; ++k) smooth = v.normal[tri[size_t(k)]] != glm::dvec3(0.0);
    float* n[3] = {sh.n0, sh.n1, sh.n2};
    float* uv[3] = {sh.uv0, sh.uv1, sh.uv2};
    for (int k = 0; k < 3; ++k) {
        store3(n[k], smooth ? v.normal[tri[size_t(k)]] : flat);
        if (!v.uv.empty()) uv[k][0] = v.uv[tri[size_t(k)]].x, uv[k][1] = v.uv[tri[size_t(k)]].y;
    }
    sh.material = material;
    if (tangents_needed_)
        for (int k = 0; k < 3; ++k) {
            std::array<float, 4> t{0.f, 0.f, 0.f, 1.f};
            if (tangent) {
                const glm::dvec4& g = (*tangent)[size_t(k)];
                t = {float(g.x), float(g.y), float(g.z), float(g.w)};
            }
            s_.tangents.push_back(t);
        }
    if (materials_.uses_texcoord1())
        for (int k = 0; k < 3; ++k) {
            glm::vec2 t = v.uv1.empty() ? glm::vec2(0.f) : v.uv1[tri[size_t(k)]];
            s_.uv1.push_back({t.x, t.y});
        }
    if (colors_needed_)
        for (int k = 0; k < 3; ++k) {
            glm::vec4 col = v.color.empty() ? glm::vec4(1.f) : v.color[tri[size_t(k)]];
            s_.colors.push_back({col.r, col.g, col.b, col.a});
        }
    s_.positions.insert(s_.positions.end(), p, p + 3);
    s_.shading.push_back(sh);
}
} // namespace clppm::gltf
