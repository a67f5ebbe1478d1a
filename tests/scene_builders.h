// Scenes built in code for the tests: quads, boxes and spheres with exactly known materials,
// lights and cameras, so that expected radiance values can be written down analytically.
#pragma once
#include <cmath>
#include <vector>

#include "io/image_io.h"
#include "scene/material_defaults.h"
#include "scene/scene.h"
#include "shared_types.h"

namespace clppm::test {

// The materials the tests build, in glTF's parameters: Lambertian (metallic 0 and
// KHR_materials_specular's specularFactor 0: no specular layer), a mirror and a GGX metal
// (metallic 1, roughness 0 or the given one), smooth glass (transmission 1).
enum TestMaterial : uint32_t { MAT_DIFFUSE, MAT_MIRROR, MAT_GLASS, MAT_METAL };

inline uint32_t add_material(Scene& s, float r, float g, float b, float emission = 0.f, bool double_sided = false,
                             TestMaterial kind = MAT_DIFFUSE, float ior = 1.5f, float roughness = 1.f) {
    dev::Material m = default_material(); // every texture absent
    m.base_color[0] = r, m.base_color[1] = g, m.base_color[2] = b, m.base_color[3] = 1;
    m.emission[0] = m.emission[1] = m.emission[2] = emission;
    m.roughness = kind == MAT_MIRROR ? 0.f : roughness;
    m.ior = ior;
    m.metallic = kind == MAT_MIRROR || kind == MAT_METAL ? 1.f : 0.f;
    m.transmission = kind == MAT_GLASS ? 1.f : 0.f;
    m.specular_color[3] = kind == MAT_DIFFUSE ? 0.f : 1.f;
    m.flags = double_sided ? MATERIAL_FLAG_DOUBLE_SIDED : 0u;
    s.materials.push_back(m);
    return uint32_t(s.materials.size() - 1);
}

inline void add_triangle(Scene& s, Vec3 a, Vec3 b, Vec3 c, uint32_t material) {
    s.positions.push_back(a), s.positions.push_back(b), s.positions.push_back(c);
    float e1[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, e2[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
    float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    float l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    dev::TriShading sh{};
    for (int k = 0; k < 3; ++k) sh.n0[k] = sh.n1[k] = sh.n2[k] = n[k] / l;
    sh.material = material;
    s.shading.push_back(sh);
}

// A quad a-b-c-d (counter-clockwise seen from the side its normal faces).
inline void add_quad(Scene& s, Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t material) {
    add_triangle(s, a, b, c, material);
    add_triangle(s, a, c, d, material);
}

// A UV sphere; normals point outwards unless `inward`. Flat triangle normals replaced by smooth ones.
inline void add_sphere(Scene& s, Vec3 c, float r, int rings, int segments, uint32_t material, bool inward = false) {
    auto point = [&](int i, int j) {
        double th = M_PI * i / rings, ph = 2 * M_PI * j / segments;
        return Vec3{float(c.x + r * std::sin(th) * std::cos(ph)), float(c.y + r * std::cos(th)),
                    float(c.z + r * std::sin(th) * std::sin(ph))};
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            Vec3 p00 = point(i, j), p01 = point(i, j + 1), p10 = point(i + 1, j), p11 = point(i + 1, j + 1);
            // Outward winding: (p00, p01, p11) seen from outside is counter-clockwise.
            Vec3 tri[2][3] = {{p00, p01, p11}, {p00, p11, p10}};
            for (auto& t : tri) {
                if (inward) std::swap(t[1], t[2]);
                size_t before = s.shading.size();
                add_triangle(s, t[0], t[1], t[2], material);
                if (s.shading.size() == before) continue;
                dev::TriShading& sh = s.shading.back();
                float* ns[3] = {sh.n0, sh.n1, sh.n2};
                for (int k = 0; k < 3; ++k) {
                    float d[3] = {t[k].x - c.x, t[k].y - c.y, t[k].z - c.z};
                    float l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * (inward ? -1.f : 1.f);
                    for (int q = 0; q < 3; ++q) ns[k][q] = d[q] / l;
                }
            }
        }
    // Drop the zero-area triangles at the poles.
    for (size_t t = 0; t < s.shading.size();) {
        const Vec3 &a = s.positions[3 * t], &b = s.positions[3 * t + 1], &cc = s.positions[3 * t + 2];
        float e1[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, e2[3] = {cc.x - a.x, cc.y - a.y, cc.z - a.z};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] < 1e-20f) {
            s.positions.erase(s.positions.begin() + 3 * t, s.positions.begin() + 3 * t + 3);
            s.shading.erase(s.shading.begin() + t);
        } else {
            ++t;
        }
    }
}

// A float[3] of a shared struct from a vector.
inline void set3(float* v, Vec3 p) { v[0] = p.x, v[1] = p.y, v[2] = p.z; }

inline void add_camera(Scene& s, Vec3 pos, Vec3 forward, Vec3 up, float yfov) {
    CameraDesc c;
    set3(c.position, pos);
    set3(c.forward, forward);
    set3(c.up, up);
    c.yfov = yfov;
    c.aspect = 1;
    s.cameras.push_back(c);
}

// A punctual light of the type with the same power in each channel (intensity, or irradiance for
// a directional light), placed and aimed by the caller.
inline dev::Light& add_light(Scene& s, uint32_t type, float power) {
    dev::Light l{};
    l.type = type;
    l.radiance[0] = l.radiance[1] = l.radiance[2] = power;
    s.punctual_lights.push_back(l);
    return s.punctual_lights.back();
}

inline void add_point_light(Scene& s, Vec3 pos, float intensity) {
    set3(add_light(s, LIGHT_POINT, intensity).position, pos);
}

// A spot light at pos pointing straight down, cones given as half-angles in radians.
inline void add_spot_light(Scene& s, Vec3 pos, float intensity, float inner, float outer) {
    dev::Light& l = add_light(s, LIGHT_SPOT, intensity);
    set3(l.position, pos);
    set3(l.direction, {0, -1, 0});
    l.cos_inner = std::cos(inner), l.cos_outer = std::cos(outer);
}

// A directional light travelling along unit direction d with irradiance E.
inline void add_directional_light(Scene& s, Vec3 d, float irradiance) {
    set3(add_light(s, LIGHT_DIRECTIONAL, irradiance).direction, d);
}

// A diffuse plane y = 0 of half-size `half`, albedo rho, seen from straight above.
inline Scene plane_under_point_light(float rho, float intensity, float light_height, float half = 4.f) {
    Scene s;
    s.source = "<plane under point light>";
    uint32_t m = add_material(s, rho, rho, rho);
    add_quad(s, {-half, 0, -half}, {-half, 0, half}, {half, 0, half}, {half, 0, -half}, m);
    add_point_light(s, {0, light_height, 0}, intensity);
    add_camera(s, {0, 3, 0}, {0, -1, 0}, {0, 0, -1}, 0.6f);
    return s;
}

// The radiance plane_under_point_light's plane (albedo rho, a point light of intensity I at height
// h) shows through pixel (px, py) of camera cam: rho / pi * I cos(theta) / d^2.
inline double plane_radiance(const dev::Camera& cam, double px, double py, double rho, double I, double h) {
    double sx = 2 * px / cam.width - 1, sy = 1 - 2 * py / cam.height;
    double d[3], o[3];
    for (int k = 0; k < 3; ++k) d[k] = cam.forward[k] + cam.right[k] * sx + cam.up[k] * sy, o[k] = cam.origin[k];
    double t = -o[1] / d[1];
    double x = o[0] + t * d[0], z = o[2] + t * d[2];
    double d2 = x * x + z * z + h * h;
    return rho / M_PI * I * (h / std::sqrt(d2)) / d2;
}

// sum |L - L_ref| / sum L_ref of channel c over the pixels [lo, hi) x [lo, hi) of a square image
// against plane_radiance; the signed sum (L - L_ref) / sum L_ref in *bias.
inline double plane_error(const Image& img, const dev::Camera& cam, int lo, int hi, int c, double rho, double I,
                          double h, double* bias = nullptr) {
    double err = 0, ref = 0, signed_err = 0;
    for (int y = lo; y < hi; ++y)
        for (int x = lo; x < hi; ++x) {
            const double expect = plane_radiance(cam, x + 0.5, y + 0.5, rho, I, h);
            const double got = img.rgb[3 * (size_t(y) * img.width + x) + c];
            err += std::fabs(got - expect);
            signed_err += got - expect;
            ref += expect;
        }
    if (bias) *bias = signed_err / ref;
    return err / ref;
}

// The white furnace: a closed sphere, albedo rho, emitting Le from both sides; the camera inside.
// Radiance everywhere is Le / (1 - rho).
inline Scene furnace(float rho, float le) {
    Scene s;
    s.source = "<furnace>";
    uint32_t m = add_material(s, rho, rho, rho, le, true);
    add_sphere(s, {0, 0, 0}, 1.f, 24, 48, m, true);
    add_camera(s, {0, 0, 0.2f}, {0, 0, -1}, {0, 1, 0}, 1.0f);
    return s;
}

// The furnace with a glossy metal enclosure (GGX, F0 = rho): energy must not grow beyond
// Le / (1 - rho), the bound a white-ish conductor's albedo (<= F0 at normal incidence... and
// below 1 everywhere) allows.
inline Scene glossy_furnace(float f0, float roughness, float le) {
    Scene s;
    s.source = "<glossy furnace>";
    uint32_t m = add_material(s, f0, f0, f0, le, true, MAT_METAL, 1.5f, roughness);
    add_sphere(s, {0, 0, 0}, 1.f, 24, 48, m, true);
    add_camera(s, {0, 0, 0.2f}, {0, 0, -1}, {0, 1, 0}, 1.0f);
    return s;
}

// A closed diffuse box with coloured walls and a square ceiling light: the diffuse-only scene PPM
// and path tracing must agree on.
inline Scene diffuse_box(bool with_blocks = true) {
    Scene s;
    s.source = "<diffuse box>";
    uint32_t white = add_material(s, 0.7f, 0.7f, 0.7f), red = add_material(s, 0.7f, 0.1f, 0.1f),
             green = add_material(s, 0.1f, 0.7f, 0.1f), light = add_material(s, 0.f, 0.f, 0.f, 12.f);
    add_quad(s, {-1, -1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, white); // floor, up
    add_quad(s, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}, white);     // ceiling, down
    add_quad(s, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, white); // back, +z
    add_quad(s, {-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}, white);     // front, -z
    add_quad(s, {-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}, {-1, -1, 1}, red);   // left, +x
    add_quad(s, {1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}, green);     // right, -x
    add_quad(s, {-0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, -0.3f}, {0.3f, 0.99f, 0.3f}, {-0.3f, 0.99f, 0.3f}, light);
    if (with_blocks) {
        // A box standing on the floor (top and four sides).
        float x0 = -0.6f, x1 = 0.0f, z0 = -0.5f, z1 = 0.1f, y1 = -0.2f;
        add_quad(s, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, white);
        add_quad(s, {x0, -1, z1}, {x1, -1, z1}, {x1, y1, z1}, {x0, y1, z1}, white);
        add_quad(s, {x0, -1, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, -1, z0}, white);
        add_quad(s, {x0, -1, z0}, {x0, -1, z1}, {x0, y1, z1}, {x0, y1, z0}, white);
        add_quad(s, {x1, -1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, -1, z1}, white);
    }
    add_camera(s, {0, 0, 0.95f}, {0, 0, -1}, {0, 1, 0}, 1.3f);
    return s;
}

// The diffuse box with a rough glossy back wall (hit points, gathered with the GGX BRDF) and a
// smooth glossy block (sampled through by eye paths).
inline Scene glossy_box() {
    Scene s = diffuse_box(false);
    s.source = "<glossy box>";
    uint32_t rough = add_material(s, 0.9f, 0.8f, 0.6f, 0.f, false, MAT_METAL, 1.5f, 0.5f);
    uint32_t smooth = add_material(s, 0.8f, 0.8f, 0.9f, 0.f, false, MAT_METAL, 1.5f, 0.12f);
    // The back wall (triangles 4 and 5 of diffuse_box) becomes rough metal.
    s.shading[4].material = s.shading[5].material = rough;
    float x0 = -0.6f, x1 = 0.0f, z0 = -0.5f, z1 = 0.1f, y1 = -0.2f;
    add_quad(s, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, smooth);
    add_quad(s, {x0, -1, z1}, {x1, -1, z1}, {x1, y1, z1}, {x0, y1, z1}, smooth);
    add_quad(s, {x0, -1, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, -1, z0}, smooth);
    add_quad(s, {x0, -1, z0}, {x0, -1, z1}, {x0, y1, z1}, {x0, y1, z0}, smooth);
    add_quad(s, {x1, -1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, -1, z1}, smooth);
    return s;
}

} // namespace clppm::test
