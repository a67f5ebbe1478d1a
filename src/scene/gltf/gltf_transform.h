// Node transforms and the small vector helpers of flattening: matrices from TRS or `matrix`,
// points and directions through them, finiteness checks.
#pragma once
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

namespace clppm::gltf {

bool finite(const glm::dmat4& m);
bool finite(const glm::dvec3& v);
glm::dmat4 rotation_matrix(const std::vector<double>& q);
bool transform_arrays_valid(const tinygltf::Node& n);
// The node's local matrix: `matrix` (column-major) or T * R * S.
glm::dmat4 local_matrix(const tinygltf::Node& n);
// T * R * S from a translation, a unit quaternion (x, y, z, w; normalised here) and a scale.
glm::dmat4 trs_matrix(const glm::dvec3& t, const std::vector<double>& q, const glm::dvec3& s);
glm::dvec3 transform_point(const glm::dmat4& m, const glm::dvec3& p);
glm::dvec3 transform_dir(const glm::dmat4& m, const glm::dvec3& d);
// Unit vector, or (0,0,0) when v has no usable direction.
glm::dvec3 unit_or_zero(const glm::dvec3& v);
void store3(float* dst, const glm::dvec3& v);

} // namespace clppm::gltf
