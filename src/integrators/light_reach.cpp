#include "integrators/light_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "scene/light_power.h"

namespace clppm {

namespace {

struct V {
    double x = 0, y = 0, z = 0;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V unit(const V& a) { return (1.0 / std::sqrt(dot(a, a))) * a; }
V vec(const Vec3& p) { return {p.x, p.y, p.z}; }
V vec(const float* p) { return {p[0], p[1], p[2]}; }

// Every triangle, brute force (Moller and Trumbore 1997), both faces.
class Triangles {
public:
    explicit Triangles(const Scene& s) {
        const size_t n = s.positions.size() / 3;
        for (size_t i = 0; i < n; ++i) {
            V a = vec(s.positions[3 * i]), b = vec(s.positions[3 * i + 1]), c = vec(s.positions[3 * i + 2]);
            v0_.push_back(a), e1_.push_back(b - a), e2_.push_back(c - a);
        }
    }
    // The closest hit in (0, tmax) other than triangle `skip`: its t and index, or t = infinity.
    std::pair<double, size_t> closest(const V& o, const V& d, double tmax, size_t skip, bool any) const {
        double best = tmax;
        size_t hit = SIZE_MAX;
        for (size_t i = 0; i < v0_.size(); ++i) {
            if (i == skip) continue;
            const V p = cross(d, e2_[i]);
            const double det = dot(e1_[i], p);
            if (std::fabs(det) < 1e-300) continue;
            const double inv = 1.0 / det;
            const V s = o - v0_[i];
            const double u = dot(s, p) * inv;
            if (u < 0 || u > 1) continue;
            const V q = cross(s, e1_[i]);
            const double v = dot(d, q) * inv;
            if (v < 0 || u + v > 1) continue;
            const double t = dot(e2_[i], q) * inv;
            if (t > 0 && t < best) {
                best = t, hit = i;
                if (any) break;
            }
        }
        return {hit == SIZE_MAX ? std::numeric_limits<double>::infinity() : best, hit};
    }
    V normal(size_t i) const { return unit(cross(e1_[i], e2_[i])); }
    V point(size_t i, double u1, double u2) const { // uniform on the triangle
        const double su = std::sqrt(u1);
        return v0_[i] + (su * (1 - u2)) * e1_[i] + (su * u2) * e2_[i];
    }
    double area(size_t i) const {
        const V c = cross(e1_[i], e2_[i]);
        return 0.5 * std::sqrt(dot(c, c));
    }
    size_t size() const { return v0_.size(); }

private:
    std::vector<V> v0_, e1_, e2_;
};

struct PilotLight {
    double power;
    size_t tri; // SIZE_MAX: punctual
    const dev::Light* punctual;
    bool two_sided;
};

// SplitMix64's numbers in [0, 1): a pilot is the same every time.
struct Numbers {
    uint64_t state = 0x9E3779B97F4A7C15ull;
    double next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    }
};

} // namespace

LightReach light_reach(const Scene& scene, const RenderSettings& settings) {
    LightReach r;
    const size_t n = scene.positions.size() / 3;
    if (scene.cameras.empty() || n == 0 || n > kLightReachMaxTriangles) return r;
    const Triangles tris(scene);
    std::vector<PilotLight> lights;
    for (size_t i = 0; i < n; ++i) {
        const dev::Material& m = scene.materials[scene.shading[i].material];
        const double le = (double(m.emission[0]) + m.emission[1] + m.emission[2]) / 3.0;
        const bool two = (m.flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0;
        if (le > 0) lights.push_back({le * tris.area(i) * (two ? 2 : 1), i, nullptr, two});
    }
    V lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const Vec3& p : scene.positions)
        lo = {std::min(lo.x, double(p.x)), std::min(lo.y, double(p.y)), std::min(lo.z, double(p.z))},
        hi = {std::max(hi.x, double(p.x)), std::max(hi.y, double(p.y)), std::max(hi.z, double(p.z))};
    const double extent = std::sqrt(dot(hi - lo, hi - lo)), eps = 1e-5 * extent;
    for (const dev::Light& l : scene.punctual_lights) {
        const double power = punctual_light_power(l, 0.5 * extent);
        if (power > 0) lights.push_back({power, SIZE_MAX, &l, false});
    }
    if (lights.empty()) return r;
    std::vector<double> cdf;
    double total = 0;
    for (const PilotLight& l : lights) cdf.push_back(total += l.power);

    const CameraDesc& cam = scene.cameras[std::min<size_t>(settings.camera, scene.cameras.size() - 1)];
    const V eye = vec(cam.position), fwd = unit(vec(cam.forward)), up = unit(vec(cam.up)), right = unit(cross(fwd, up));
    const double aspect = cam.aspect > 0                      ? cam.aspect
                          : settings.width && settings.height ? double(settings.width) / settings.height
                                                              : 1.0;
    const double ty = std::tan(0.5 * cam.yfov), tx = ty * aspect;
    constexpr int kGrid = 8, kSamples = 4;
    Numbers u;
    uint64_t samples = 0, lit = 0;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const double sx = 2 * (i + 0.5) / kGrid - 1, sy = 1 - 2 * (j + 0.5) / kGrid;
            V o = eye, d = fwd;
            if (cam.orthographic) o = eye + (sx * cam.xmag) * right + (sy * cam.ymag) * up;
            else d = unit(fwd + (sx * tx) * right + (sy * ty) * up);
            const auto [t, tri] = tris.closest(o, d, 1e300, SIZE_MAX, false);
            if (tri == SIZE_MAX) continue;
            ++r.hits;
            V nx = tris.normal(tri);
            if (dot(nx, d) > 0) nx = -1.0 * nx; // the side the camera sees
            const V x = o + t * d + eps * nx;
            for (int k = 0; k < kSamples; ++k) {
                ++samples;
                const size_t li = size_t(std::upper_bound(cdf.begin(), cdf.end(), u.next() * total) - cdf.begin());
                const PilotLight& L = lights[std::min(li, lights.size() - 1)];
                V w;
                double dist = 4 * extent;
                if (L.tri != SIZE_MAX) {
                    if (L.tri == tri) { // the camera sees the emitter itself: lit
                        ++lit;
                        continue;
                    }
                    const V q = tris.point(L.tri, u.next(), u.next());
                    dist = std::sqrt(dot(q - x, q - x));
                    w = (1.0 / dist) * (q - x);
                    const double cl = dot(tris.normal(L.tri), -1.0 * w);
                    if (!(cl > 0 || (L.two_sided && cl < 0))) continue;
                } else if (L.punctual->type == LIGHT_DIRECTIONAL) {
                    w = -1.0 * unit(vec(L.punctual->direction));
                } else {
                    const V q = vec(L.punctual->position);
                    dist = std::sqrt(dot(q - x, q - x));
                    w = (1.0 / dist) * (q - x);
                    if (L.punctual->type == LIGHT_SPOT &&
                        dot(-1.0 * w, unit(vec(L.punctual->direction))) < L.punctual->cos_outer)
                        continue;
                }
                if (!(dot(w, nx) > 0)) continue;
                if (tris.closest(x, w, dist * (1 - 1e-6), L.tri, true).second == SIZE_MAX) ++lit;
            }
        }
    r.measured = r.hits > 0;
    r.lit = samples ? double(lit) / double(samples) : 0;
    return r;
}

} // namespace clppm
