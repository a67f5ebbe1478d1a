// Tangent frames for normal mapping where a file gives none, in the MikkTSpace convention that
// glTF 2.0 (Sec. 3.7.2.1) asks for: the tangent is the direction of increasing u made orthogonal
// to the vertex normal, and its sign w makes cross(normal, tangent) w point along decreasing v
// (glTF's v runs down the image, so that is the image's up: the normal map's +Y).
//
// Each triangle's dp/du and dp/dv are summed at its corners weighted by the corner's angle, as
// MikkTSpace does, separately for triangles of either handedness (MikkTSpace's vertex split, so
// mirrored uv islands sharing a vertex do not cancel); triangles whose uv map is degenerate take
// their neighbours' frame. What is not reproduced is MikkTSpace's exact treatment of degenerate
// and non-manifold cases, so a map baked by a MikkTSpace tool matches wherever the uv layout is
// regular.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace clppm::gltf {

// Per corner of the triangles idx (three vertex indices each) of a primitive with world-space
// positions, normals (empty: the triangles' own) and texture coordinates: xyz the unit tangent
// (zero where none can be made), w = +-1.
std::vector<glm::dvec4> generate_tangents(const std::vector<uint32_t>& idx, const std::vector<glm::dvec3>& position,
                                          const std::vector<glm::dvec3>& normal, const std::vector<glm::vec2>& uv);

} // namespace clppm::gltf
