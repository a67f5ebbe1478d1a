#include "scene/gltf/gltf_skin.h"

#include <cmath>

#include "scene/gltf/gltf_transform.h"

namespace clppm::gltf {

std::vector<glm::dmat4> joint_matrices(const tinygltf::Model& m, const AccessorReader& reader, const LoadContext& ctx,
                                       int skin, const std::string& label) {
    if (skin < 0 || size_t(skin) >= m.skins.size()) ctx.fail(label + " skin " + std::to_string(skin) + " out of range");
    const tinygltf::Skin& s = m.skins[size_t(skin)];
    const std::string what = labelled("skin", skin, s.name);
    // Each node's parent (the first that lists it), for global transforms of joints anywhere.
    std::vector<int> parent(m.nodes.size(), -1);
    for (size_t i = 0; i < m.nodes.size(); ++i)
        for (int c : m.nodes[i].children)
            if (c >= 0 && size_t(c) < m.nodes.size() && parent[size_t(c)] < 0) parent[size_t(c)] = int(i);
    // Global transforms, memoised: each node is composed once however many joints sit below it
    // (a hostile file cannot make this quadratic).
    std::vector<glm::dmat4> memo(m.nodes.size());
    std::vector<char> done(m.nodes.size(), 0);
    auto global = [&](int n) {
        std::vector<int> chain; // n and its ancestors up to the first known one
        for (int a = n; a >= 0 && !done[size_t(a)]; a = parent[size_t(a)]) {
            if (chain.size() > m.nodes.size()) ctx.fail(what + ": node graph cycle above a joint");
            chain.push_back(a);
        }
        for (size_t i = chain.size(); i-- > 0;) {
            const int a = chain[i];
            const tinygltf::Node& node = m.nodes[size_t(a)];
            if (!transform_arrays_valid(node))
                ctx.fail(labelled("node", a, node.name) + " has a transform array of the wrong length");
            const int p = parent[size_t(a)];
            memo[size_t(a)] = (p >= 0 ? memo[size_t(p)] : glm::dmat4(1.0)) * local_matrix(node);
            done[size_t(a)] = 1;
        }
        return memo[size_t(n)];
    };
    AccessorView ibm;
    if (s.inverseBindMatrices >= 0) {
        ibm = reader.view(s.inverseBindMatrices, what + " inverseBindMatrices");
        if (ibm.components != 16 || ibm.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT || ibm.count < s.joints.size())
            ctx.fail(what + ": inverseBindMatrices must be a MAT4 of FLOAT with one matrix per joint");
    }
    std::vector<glm::dmat4> j(s.joints.size());
    for (size_t k = 0; k < s.joints.size(); ++k) {
        const int n = s.joints[k];
        if (n < 0 || size_t(n) >= m.nodes.size())
            ctx.fail(what + " joint " + std::to_string(k) + " is node " + std::to_string(n) + ", out of range");
        glm::dmat4 inv(1.0);
        if (s.inverseBindMatrices >= 0)
            for (int c = 0; c < 16; ++c) inv[c / 4][c % 4] = ibm.get(k, c); // column-major
        j[k] = global(n) * inv;
        if (!finite(j[k])) ctx.fail(what + " joint " + std::to_string(k) + " has a non-finite transform");
    }
    return j;
}

void apply_skin(const tinygltf::Primitive& prim, const std::vector<glm::dmat4>& joints, const AccessorReader& reader,
                const LoadContext& ctx, const std::string& label, WorldVertices* v) {
    const size_t n = v->position.size();
    std::vector<glm::dmat4> blend(n, glm::dmat4(0.0));
    std::vector<double> total(n, 0.0);
    for (int set = 0;; ++set) {
        const std::string js = "JOINTS_" + std::to_string(set), ws = "WEIGHTS_" + std::to_string(set);
        if (!prim.attributes.count(js) || !prim.attributes.count(ws)) break;
        AccessorView jv = reader.view(prim.attributes.at(js), label + " " + js);
        AccessorView wv = reader.view(prim.attributes.at(ws), label + " " + ws);
        const bool joint_type = jv.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                jv.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
        if (jv.components != 4 || !joint_type || jv.normalized)
            ctx.fail(label + ": " + js + " must be a VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT");
        const bool weight_type = wv.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                                 (wv.normalized && (wv.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                    wv.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
        if (wv.components != 4 || !weight_type)
            ctx.fail(label + ": " + ws + " must be a VEC4 of FLOAT or normalized UNSIGNED_BYTE/SHORT");
        if (jv.count < n || wv.count < n)
            ctx.fail(label + ": " + js + " or " + ws + " has fewer elements than POSITION");
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 4; ++c) {
                const double w = wv.get(i, c);
                if (!(w > 0.0)) continue;
                const size_t k = size_t(jv.get(i, c));
                if (k >= joints.size())
                    ctx.fail(label + ": " + js + " names joint " + std::to_string(k) + " of a skin with " +
                             std::to_string(joints.size()));
                blend[i] += w * joints[k];
                total[i] += w;
            }
    }
    for (size_t i = 0; i < n; ++i) {
        if (!(total[i] > 0.0)) continue; // no weight: where the mesh put it
        const glm::dmat4 mat = blend[i] / total[i];
        v->position[i] = transform_point(mat, v->position[i]);
        const glm::dmat3 linear(mat);
        const double det = glm::determinant(linear);
        if (!v->normal.empty()) {
            const glm::dmat3 nm = std::abs(det) > 1e-300 ? glm::transpose(glm::inverse(linear)) : glm::dmat3(0.0);
            v->normal[i] = unit_or_zero(nm * v->normal[i]);
        }
        if (!v->tangent.empty()) {
            const glm::dvec3 t = unit_or_zero(linear * glm::dvec3(v->tangent[i]));
            v->tangent[i] = glm::dvec4(t, v->tangent[i].w * (det < 0 ? -1.0 : 1.0));
        }
    }
}

} // namespace clppm::gltf
