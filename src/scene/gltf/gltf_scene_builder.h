// Flattening a parsed glTF into the Scene: the node hierarchy walked depth-first (cycles and
// instancing bombs refused), each mesh instance's primitives turned into world-space triangles,
// with materials, lights and cameras converted by their own classes.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/gltf/gltf_accessors.h"
#include "scene/gltf/gltf_context.h"
#include "scene/gltf/gltf_lights_cameras.h"
#include "scene/gltf/gltf_materials.h"

namespace clppm::gltf {

// World-space vertex data of one primitive instance.
struct WorldVertices {
    std::vector<glm::dvec3> position;
    std::vector<glm::dvec3> normal;  // empty: none in the file; (0,0,0): unusable
    std::vector<glm::vec2> uv;       // empty: none
    std::vector<glm::vec2> uv1;      // TEXCOORD_1 where a texture reads it; empty: none
    std::vector<glm::dvec4> tangent; // empty: none (xyz world tangent, w bitangent sign)
    std::vector<glm::vec4> color;    // COLOR_0, linear RGBA; empty: none
};

// Primitive modes with area (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN), their names otherwise, and
// how many triangles a mode assembles from a vertex sequence.
bool is_triangle_mode(int mode);
const char* mode_name(int mode);
size_t triangle_count(int mode, size_t vertices);

class SceneBuilder {
public:
    SceneBuilder(const tinygltf::Model& m, LoadContext& ctx, Scene& s)
        : m_(m), ctx_(ctx), s_(s), reader_(m, ctx), materials_(m, ctx, s), lights_cameras_(m, ctx, s) {}

    // Fills the scene: materials, then every triangle, light and camera of the default scene.
    void build();

private:
    void warn_unsupported_extensions();

    std::vector<int> root_nodes();

    // Without a `scenes` array, render every node that is nobody's child.
    std::vector<int> parentless_nodes();

    struct Frame; // a node on the traversal's stack

    // Depth-first with an explicit stack (no recursion limit on deep chains); a node already on
    // the current path is its own ancestor: a cycle.
    void traverse(const std::vector<int>& roots);

    std::string node_label(int index) const { return labelled("node", index, m_.nodes[size_t(index)].name); }

    // Labels are built only on the way to an error: shared subtrees make this path hot.
    void enter(int index, const glm::dmat4& parent, int parent_index, std::vector<Frame>& stack);

    void instantiate(int index, const glm::dmat4& world);

    // -- meshes --

    // Adds the triangles an instance of `mesh` will add (an upper bound: degenerate ones count).
    void count_triangles(int mesh);

    void add_mesh(int mesh, const glm::dmat4& world, const std::string& node_label);

    AccessorView attribute(const tinygltf::Primitive& prim, const char* name, const std::string& label);

    void require(bool ok, const std::string& what);

    WorldVertices world_vertices(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label);

    // Normals by the inverse transpose, so they stay perpendicular under non-uniform scale.
    void read_normals(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label,
                      WorldVertices* v);

    void read_uvs(const tinygltf::Primitive& prim, const std::string& label, const char* name,
                  std::vector<glm::vec2>* out, size_t vertices);

    // TANGENT: xyz by the world transform's linear part, w negated by a mirroring transform.
    void read_tangents(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label,
                       WorldVertices* v);

    // Vertex indices of the primitive, three per triangle, assembled by its mode (TRIANGLES,
    // TRIANGLE_STRIP, TRIANGLE_FAN).
    std::vector<uint32_t> triangle_indices(const tinygltf::Primitive& prim, size_t vertex_count,
                                           const std::string& label);
    std::vector<uint32_t> vertex_sequence(const tinygltf::Primitive& prim, size_t vertex_count,
                                          const std::string& label);

    // -- EXT_mesh_gpu_instancing --
    const tinygltf::Value* instancing_attributes(const tinygltf::Node& node, const std::string& label);
    int instancing_accessor(const tinygltf::Value& attributes, const char* name, const std::string& label);
    // How many times the node's mesh is drawn: 1 unless the extension gives per-instance TRS.
    size_t gpu_instance_count(const tinygltf::Node& node, const std::string& label);
    // The per-instance T * R * S matrices (empty: not instanced).
    std::vector<glm::dmat4> gpu_instances(const tinygltf::Node& node, const std::string& label);

    void reserve_triangles(size_t count);

    void add_primitive(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label);

    // tangent: the corners' tangent frames (null: none).
    void add_triangle(const std::array<uint32_t, 3>& tri, const WorldVertices& v, uint32_t material,
                      const std::array<glm::dvec4, 3>* tangent);

    bool tangents_needed_ = false; // some material has a normalTexture
    bool colors_needed_ = false;   // some primitive has COLOR_0

    void read_colors(const tinygltf::Primitive& prim, const std::string& label, WorldVertices* v);

    const tinygltf::Model& m_;
    LoadContext& ctx_;
    Scene& s_;
    AccessorReader reader_;
    MaterialConverter materials_;
    LightsAndCameras lights_cameras_;
    std::set<int> meshes_without_normals_;
    std::vector<char> on_path_;
    const std::vector<glm::dmat4>* skin_ = nullptr; // the joint matrices of the mesh being added, if skinned
    std::map<int, std::vector<glm::dmat4>> joints_; // per skin, computed once
    size_t visits_ = 0;
    bool counting_ = false;          // the first traversal: count, build nothing
    size_t instanced_triangles_ = 0; // counted so far, all instances
    std::map<int, size_t> mesh_triangles_;
};

} // namespace clppm::gltf
