#include "scene/gltf/gltf_transform.h"

#include <cmath>

#include "util/narrow_to_float.h"

namespace clppm::gltf {

bool finite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::dmat4 rotation_matrix(const std::vector<double>& q) {
    double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double x = q[0] / len, y = q[1] / len, z = q[2] / len, w = q[3] / len;
    glm::dmat4 r(1.0); // r[column][row]
    r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0};
    r[1] = {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0};
    r[2] = {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0};
    return r;
}

bool transform_arrays_valid(const tinygltf::Node& n) {
    auto ok = [](const std::vector<double>& v, size_t want) { return v.empty() || v.size() == want; };
    return ok(n.matrix, 16) && ok(n.translation, 3) && ok(n.rotation, 4) && ok(n.scale, 3);
}

glm::dmat4 local_matrix(const tinygltf::Node& n) {
    glm::dmat4 m(1.0);
    if (!n.matrix.empty()) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c * 4 + r)];
        return m;
    }
    glm::dvec3 t =
        n.translation.empty() ? glm::dvec3(0.0) : glm::dvec3(n.translation[0], n.translation[1], n.translation[2]);
    glm::dvec3 s = n.scale.empty() ? glm::dvec3(1.0) : glm::dvec3(n.scale[0], n.scale[1], n.scale[2]);
    return trs_matrix(t, n.rotation.empty() ? std::vector<double>{0, 0, 0, 1} : n.rotation, s);
}

glm::dmat4 trs_matrix(const glm::dvec3& t, const std::vector<double>& q, const glm::dvec3& s) {
    glm::dmat4 m = rotation_matrix(q);
    m[3] = {t.x, t.y, t.z, 1.0};
    for (int c = 0; c < 3; ++c) m[c] *= s[c];
    return m;
}

glm::dvec3 transform_point(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }
glm::dvec3 transform_dir(const glm::dmat4& m, const glm::dvec3& d) { return glm::dvec3(m * glm::dvec4(d, 0.0)); }

glm::dvec3 unit_or_zero(const glm::dvec3& v) {
    double len = glm::length(v);
    return (std::isfinite(len) && len > 1e-30) ? v / len : glm::dvec3(0.0);
}

void store3(float* dst, const glm::dvec3& v) {
    dst[0] = narrow_to_float(v.x), dst[1] = narrow_to_float(v.y), dst[2] = narrow_to_float(v.z);
}

} // namespace clppm::gltf
