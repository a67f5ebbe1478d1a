#include "scene/volume_nesting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "scene/bvh_build.h"
#include "scene/used_materials.h"

namespace clppm {
namespace {

using D3 = std::array<double, 3>;

D3 d3(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 cross(const D3& a, const D3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

bool encloses(const dev::Material& m) { return (m.flags & MATERIAL_FLAG_ENCLOSES_VOLUME) != 0u; }

// A crossing of a volume's face along a ray: its distance, the triangle, and whether the ray
// enters there (the face's front, as wound: kernels/medium.cl's convention).
struct Crossing {
    double t;
    uint32_t tri;
    bool enters;
};

// The volumes' triangles in a BVH, and every crossing of a ray with them.
class VolumeFaces {
public:
    VolumeFaces(const Scene& scene, std::vector<uint32_t> tris) : scene_(scene), tris_(std::move(tris)) {
        std::vector<Vec3> positions;
        positions.reserve(3 * tris_.size());
        for (uint32_t t : tris_)
            for (int k = 0; k < 3; ++k) positions.push_back(scene.positions[3 * size_t(t) + size_t(k)]);
        BvhBuildResult bvh = build_bvh(positions);
        nodes_ = std::move(bvh.nodes);
        order_ = std::move(bvh.tri_order);
    }

    // The crossings of o + t d, t > 0, with the faces of materials other than `skip`, nearest first.
    std::vector<Crossing> crossings(const D3& o, const D3& d, uint32_t skip) const {
        std::vector<Crossing> out;
        if (tris_.empty()) return out;
        const D3 inv = {1.0 / d[0], 1.0 / d[1], 1.0 / d[2]};
        std::vector<int32_t> stack{0};
        while (!stack.empty()) {
            const dev::BvhNode& n = nodes_[size_t(stack.back())];
            stack.pop_back();
            for (int c = 0; c < BVH_WIDTH; ++c) {
                if (n.child[c] == -1 && n.count[c] == 0) continue;
                if (!slab(n, c, o, inv)) continue;
                if (n.child[c] >= 0) {
                    stack.push_back(n.child[c]);
                    continue;
                }
                const uint32_t first = ~uint32_t(n.child[c]);
                for (uint32_t i = first; i < first + n.count[c]; ++i) {
                    const uint32_t tri = tris_[order_[i]];
                    if (scene_.shading[tri].material == skip) continue;
                    cross_triangle(tri, o, d, &out);
                }
            }
        }
        std::sort(out.begin(), out.end(), [](const Crossing& a, const Crossing& b) { return a.t < b.t; });
        return out;
    }

    // The face of the innermost volume (not of material `skip`) around p, or kNoEnclosure: the
    // first face left along a ray whose volume was not entered on the way, by a majority of rays in
    // three directions no axis-aligned wall or edge lies along.
    uint32_t container(const D3& p, uint32_t skip) const {
        static const D3 kDirs[3] = {{0.5773, 0.5781, 0.5766}, {-0.6234, 0.4517, -0.6381}, {0.3128, -0.8237, 0.4729}};
        std::map<uint32_t, int> votes; // by the container's material; the face of its first vote kept
        std::map<uint32_t, uint32_t> face_of;
        for (const D3& d : kDirs) {
            const uint32_t e = first_exit(crossings(p, d, skip));
            const uint32_t key = e == kNoEnclosure ? kNoEnclosure : scene_.shading[e].material;
            ++votes[key];
            face_of.emplace(key, e);
        }
        const auto best = std::max_element(votes.begin(), votes.end(),
                                           [](const auto& a, const auto& b) { return a.second < b.second; });
        return face_of[best->first];
    }

private:
    uint32_t first_exit(const std::vector<Crossing>& crossings) const {
        std::map<uint32_t, int> entered;
        for (const Crossing& c : crossings) {
            const uint32_t m = scene_.shading[c.tri].material;
            if (c.enters) {
                ++entered[m];
            } else if (entered[m] > 0) {
                --entered[m];
            } else {
                return c.tri;
            }
        }
        return kNoEnclosure;
    }

    static bool slab(const dev::BvhNode& n, int c, const D3& o, const D3& inv) {
        const double lo[3] = {n.bmin_x[c], n.bmin_y[c], n.bmin_z[c]}, hi[3] = {n.bmax_x[c], n.bmax_y[c], n.bmax_z[c]};
        double t0 = 0, t1 = INFINITY;
        for (int k = 0; k < 3; ++k) {
            double a = (lo[k] - o[size_t(k)]) * inv[size_t(k)], b = (hi[k] - o[size_t(k)]) * inv[size_t(k)];
            if (a > b) std::swap(a, b);
            t0 = std::max(t0, a);
            t1 = std::min(t1, b * (1 + 1e-12));
        }
        return t0 <= t1;
    }

    // Moller-Trumbore in double.
    void cross_triangle(uint32_t tri, const D3& o, const D3& d, std::vector<Crossing>* out) const {
        const D3 v0 = d3(scene_.positions[3 * size_t(tri)]);
        const D3 e1 = sub(d3(scene_.positions[3 * size_t(tri) + 1]), v0);
        const D3 e2 = sub(d3(scene_.positions[3 * size_t(tri) + 2]), v0);
        const D3 p = cross(d, e2);
        const double det = dot(e1, p);
        if (det == 0) return;
        const D3 s = sub(o, v0);
        const double u = dot(s, p) / det;
        if (u < 0 || u > 1) return;
        const D3 q = cross(s, e1);
        const double v = dot(d, q) / det;
        if (v < 0 || u + v > 1) return;
        const double t = dot(e2, q) / det;
        if (t > 0) out->push_back({t, tri, dot(cross(e1, e2), d) < 0});
    }

    const Scene& scene_;
    std::vector<uint32_t> tris_;
    std::vector<dev::BvhNode> nodes_;
    std::vector<uint32_t> order_;
};

} // namespace

Enclosures enclosures(const Scene& scene) {
    const size_t n = scene.num_triangles();
    Enclosures out;
    out.triangles.assign(n, kNoEnclosure);
    out.lights.assign(scene.punctual_lights.size(), kNoEnclosure);
    const std::vector<bool> used = used_materials(scene);
    // Each volume material's bounds: a triangle outside all others' cannot be enclosed.
    std::map<uint32_t, std::pair<D3, D3>> bounds;
    std::vector<uint32_t> faces;
    for (uint32_t t = 0; t < n; ++t) {
        const uint32_t m = scene.shading[t].material;
        if (m >= scene.materials.size() || !used[m] || !encloses(scene.materials[m])) continue;
        faces.push_back(t);
        auto it =
            bounds.emplace(m, std::make_pair(D3{INFINITY, INFINITY, INFINITY}, D3{-INFINITY, -INFINITY, -INFINITY}))
                .first;
        for (int k = 0; k < 3; ++k) {
            const D3 p = d3(scene.positions[3 * size_t(t) + size_t(k)]);
            for (size_t a = 0; a < 3; ++a)
                it->second.first[a] = std::min(it->second.first[a], p[a]),
                it->second.second[a] = std::max(it->second.second[a], p[a]);
        }
    }
    if (bounds.empty()) return out;
    const VolumeFaces volumes(scene, faces);
    for (uint32_t t = 0; t < n; ++t) {
        const uint32_t m = scene.shading[t].material;
        D3 c{};
        for (int k = 0; k < 3; ++k) {
            const D3 p = d3(scene.positions[3 * size_t(t) + size_t(k)]);
            for (size_t a = 0; a < 3; ++a) c[a] += p[a] / 3;
        }
        bool candidate = false;
        for (const auto& b : bounds) {
            if (b.first == m) continue;
            bool in = true;
            for (size_t a = 0; a < 3; ++a) in = in && c[a] >= b.second.first[a] && c[a] <= b.second.second[a];
            candidate = candidate || in;
        }
        if (!candidate) continue;
        out.triangles[t] = volumes.container(c, m);
    }
    for (size_t l = 0; l < scene.punctual_lights.size(); ++l) {
        const dev::Light& light = scene.punctual_lights[l];
        if (light.type == LIGHT_DIRECTIONAL) continue;
        out.lights[l] = volumes.container({light.position[0], light.position[1], light.position[2]}, kNoEnclosure);
    }
    return out;
}

void nest_volumes(Scene& scene) {
    const Enclosures enclosed = enclosures(scene);
    const std::vector<uint32_t>& container = enclosed.triangles;
    const size_t n = scene.num_triangles();
    auto none = [](const std::vector<uint32_t>& v) {
        return std::all_of(v.begin(), v.end(), [](uint32_t c) { return c == kNoEnclosure; });
    };
    if (none(container) && none(enclosed.lights)) return;
    // The final material of each triangle, resolved containers first: (material, outside) pairs
    // each get one material, the first pair of a material its own index.
    std::vector<uint32_t> final_material(n, kNoEnclosure);
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> made;
    std::vector<bool> claimed(scene.materials.size(), false);
    std::vector<bool> visiting(n, false);
    const size_t named = scene.material_names.size();
    auto resolve = [&](uint32_t t, auto&& self) -> uint32_t {
        if (final_material[t] != kNoEnclosure) return final_material[t];
        uint32_t outside = 0;
        const uint32_t c = container[t];
        if (c != kNoEnclosure && !visiting[t]) { // a cycle (crossed meshes) falls back to the world
            visiting[t] = true;
            outside = self(c, self) + 1;
            visiting[t] = false;
        }
        const uint32_t m = scene.shading[t].material;
        const auto key = std::make_pair(m, outside);
        auto it = made.find(key);
        if (it == made.end()) {
            uint32_t index = m;
            if (claimed[m]) {
                index = uint32_t(scene.materials.size());
                dev::Material copy = scene.materials[m];
                scene.materials.push_back(copy);
                if (m < named) {
                    scene.material_names.resize(index, "");
                    scene.material_names.push_back(scene.material_names[m]);
                }
            }
            claimed[m] = true;
            scene.materials[index].outside = outside;
            it = made.emplace(key, index).first;
        }
        return final_material[t] = it->second;
    };
    for (uint32_t t = 0; t < n; ++t) resolve(t, resolve);
    for (uint32_t t = 0; t < n; ++t) scene.shading[t].material = final_material[t];
    // The volumes that hold a light: the path tracer samples lights from their media.
    auto holds_light = [&](uint32_t outside) {
        if (outside > 0) scene.materials[outside - 1].flags |= MATERIAL_FLAG_HOLDS_LIGHTS;
    };
    for (uint32_t t = 0; t < n; ++t) {
        const dev::Material& m = scene.materials[final_material[t]];
        if (m.emission[0] > 0.f || m.emission[1] > 0.f || m.emission[2] > 0.f) holds_light(m.outside);
    }
    for (uint32_t c : enclosed.lights)
        if (c != kNoEnclosure) holds_light(final_material[c] + 1);
}

} // namespace clppm
