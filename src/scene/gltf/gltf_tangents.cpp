#include "scene/gltf/gltf_tangents.h"

#include <algorithm>
#include <cmath>

namespace clppm::gltf {

namespace {

glm::dvec3 unit(const glm::dvec3& v) {
    double l = glm::length(v);
    return (std::isfinite(l) && l > 1e-300) ? v / l : glm::dvec3(0.0);
}

// The angle at corner a of triangle (a, b, c).
double corner_angle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    glm::dvec3 u = unit(b - a), w = unit(c - a);
    return std::acos(std::clamp(glm::dot(u, w), -1.0, 1.0));
}

} // namespace

std::vector<glm::dvec4> generate_tangents(const std::vector<uint32_t>& idx, const std::vector<glm::dvec3>& position,
                                          const std::vector<glm::dvec3>& normal, const std::vector<glm::vec2>& uv) {
    const size_t faces = idx.size() / 3;
    // Per face: dp/du, dp/dv (Lengyel's solution of the two edge equations), handedness, normal.
    std::vector<glm::dvec3> dpdu(faces), dpdv(faces), face_n(faces);
    std::vector<int> side(faces, 0); // +1, -1, 0: degenerate uv map
    for (size_t f = 0; f < faces; ++f) {
        const uint32_t* t = &idx[3 * f];
        glm::dvec3 e1 = position[t[1]] - position[t[0]], e2 = position[t[2]] - position[t[0]];
        glm::dvec2 d1 = glm::dvec2(uv[t[1]] - uv[t[0]]), d2 = glm::dvec2(uv[t[2]] - uv[t[0]]);
        face_n[f] = unit(glm::cross(e1, e2));
        // Handedness is relative to the shading normals (a mirroring transform reverses the
        // winding, not the normals the file gives).
        if (!normal.empty() && glm::dot(face_n[f], normal[t[0]] + normal[t[1]] + normal[t[2]]) < 0)
            face_n[f] = -face_n[f];
        double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::fabs(det) > 1e-20) || !std::isfinite(det)) continue;
        dpdu[f] = (e1 * d2.y - e2 * d1.y) / det;
        dpdv[f] = (e2 * d1.x - e1 * d2.x) / det;
        // Right-handed when (dp/du, -dp/dv, n) is: then w = +1.
        side[f] = glm::dot(glm::cross(face_n[f], dpdu[f]), -dpdv[f]) < 0 ? -1 : 1;
    }
    // Angle-weighted sums per vertex and handedness (index 0: w = +1, 1: w = -1).
    std::vector<glm::dvec3> sum_u(2 * position.size(), glm::dvec3(0.0));
    for (size_t f = 0; f < faces; ++f) {
        if (!side[f]) continue;
        const uint32_t* t = &idx[3 * f];
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& a = position[t[k]];
            double angle = corner_angle(a, position[t[(k + 1) % 3]], position[t[(k + 2) % 3]]);
            sum_u[2 * t[k] + (side[f] < 0)] += angle * unit(dpdu[f]);
        }
    }
    std::vector<glm::dvec4> out(idx.size(), glm::dvec4(0.0, 0.0, 0.0, 1.0));
    for (size_t f = 0; f < faces; ++f) {
        const uint32_t* t = &idx[3 * f];
        for (int k = 0; k < 3; ++k) {
            const uint32_t vtx = t[k];
            glm::dvec3 n = normal.empty() || normal[vtx] == glm::dvec3(0.0) ? face_n[f] : normal[vtx];
            // A face with a degenerate uv map takes the frame the vertex has, preferring w = +1.
            int s = side[f] ? side[f] : (sum_u[2 * vtx] != glm::dvec3(0.0) ? 1 : -1);
            glm::dvec3 u = sum_u[2 * vtx + (s < 0)];
            glm::dvec3 tangent = unit(u - n * glm::dot(n, u));
            out[3 * f + size_t(k)] = glm::dvec4(tangent, double(s));
        }
    }
    return out;
}

} // namespace clppm::gltf
