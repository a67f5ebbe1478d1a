// The scenes and checks shared by the tests of participating media (medium_test.cpp, the path
// tracer's; medium_photons_test.cpp, the photon integrators'): a glowing closed box with the camera
// inside, the same with a scattering index-matched cube, and the host references that the images
// are held against.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>

#include "scene/scene.h"
#include "scene_builders.h"
#include "test_util.h"

namespace clppm::test {

// An axis-aligned box of half-size h about c as 12 triangles, normals outwards (or inwards).
inline void add_box(Scene& s, Vec3 c, float h, uint32_t material, bool inward) {
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            auto corner = [&](float a, float b) {
                float p[3];
                p[axis] = sign * h, p[u] = a * h, p[v] = b * h;
                return Vec3{c.x + p[0], c.y + p[1], c.z + p[2]};
            };
            // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
            const bool out = (sign > 0) != inward;
            if (out) add_quad(s, corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1), material);
            else add_quad(s, corner(-1, -1), corner(-1, 1), corner(1, 1), corner(1, -1), material);
        }
}

// The camera at the origin looking down -z inside a closed box of half-size 1 whose walls reflect
// rho and glow Le from both sides.
inline Scene glowing_box(float rho, float le) {
    Scene s;
    s.source = "<glowing box>";
    add_box(s, {0, 0, 0}, 1.f, add_material(s, rho, rho, rho, le, true), true);
    add_camera(s, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.0f);
    return s;
}

inline void set_medium(Scene& s, std::array<float, 3> density, std::array<float, 3> albedo, float g) {
    s.medium.present = true;
    s.medium.medium = MediumDesc{density, albedo, g};
    s.medium.source = "<test>";
}

inline RenderSettings pt_settings(unsigned size, unsigned max_bounces = 16) {
    RenderSettings s;
    s.width = s.height = size;
    s.integrator = "pt";
    s.max_bounces = max_bounces;
    return s;
}

// Entry and exit distances of the unit-direction ray o + t d through the box |p - c| <= h (t_in > t_out: a miss).
inline void slab(D3 o, D3 d, D3 c, double h, double* t_in, double* t_out) {
    double lo = -INFINITY, hi = INFINITY;
    const double oo[3] = {o.x - c.x, o.y - c.y, o.z - c.z}, dd[3] = {d.x, d.y, d.z};
    for (int k = 0; k < 3; ++k) {
        const double a = (-h - oo[k]) / dd[k], b = (h - oo[k]) / dd[k];
        lo = std::max(lo, std::min(a, b));
        hi = std::min(hi, std::max(a, b));
    }
    *t_in = lo, *t_out = hi;
}

// The mean over pixel (px, py) of f(unit ray direction), on an n x n grid of the pixel's points.
inline double pixel_mean(const dev::Camera& cam, int px, int py, int n, const std::function<double(D3)>& f) {
    double sum = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double sx = 2 * (px + (i + 0.5) / n) / cam.width - 1, sy = 1 - 2 * (py + (j + 0.5) / n) / cam.height;
            const D3 d = d3(cam.forward) + sx * d3(cam.right) + sy * d3(cam.up);
            sum += f(normalized(d));
        }
    return sum / (n * n);
}

inline dev::Camera camera_of(const Scene& scene, const RenderSettings& s) {
    float bmin[3] = {-1, -1, -1}, bmax[3] = {1, 1, 1};
    return make_camera(scene, s, bmin, bmax, nullptr);
}

// The image's mean in channel c over the square [lo, hi)^2 against the reference's over the same
// pixels, within tol; returns their ratio.
inline double expect_region(const Image& img, const dev::Camera& cam, int lo, int hi, int c, double tol,
                            const std::function<double(D3)>& ref, const std::string& what) {
    double want = 0;
    for (int y = lo; y < hi; ++y)
        for (int x = lo; x < hi; ++x) want += pixel_mean(cam, x, y, 4, ref);
    want /= double((hi - lo) * (hi - lo));
    const double got = region_mean(img, lo, lo, hi, hi, c);
    EXPECT_NEAR(got / want, 1.0, tol) << what << ", channel " << c << ": " << got << " against " << want;
    return got / want;
}

inline void expect_clean(const Image& img) {
    EXPECT_EQ(count_nonfinite(img), 0u);
    for (float v : img.rgb) ASSERT_GE(v, 0.f);
}

// glowing_box's scene rendered by the path tracer at 24 x 24 for 256 passes, checked clean, with its camera.
struct Rendered {
    Image img;
    dev::Camera cam;
};
inline Rendered render_box(const Scene& scene) {
    const RenderSettings s = pt_settings(24);
    Rendered r{render_passes(scene, s, 256), camera_of(scene, s)};
    expect_clean(r.img);
    return r;
}

// glowing_box's room with, just inside its walls, an index-matched glass cube (ior 1: no
// refraction, no reflection) whose volume scatters: the camera is inside the cube.
inline Scene scattering_cube(float rho, std::array<float, 3> sigma, std::array<float, 3> albedo, float g) {
    Scene scene = glowing_box(rho, 1.f);
    const uint32_t m = add_material(scene, 1, 1, 1, 0, false, MAT_GLASS, 1.f, 0.f);
    dev::Material& glass = scene.materials[m];
    glass.flags |= MATERIAL_FLAG_ENCLOSES_VOLUME;
    for (int k = 0; k < 3; ++k) glass.attenuation[k] = sigma[size_t(k)], glass.scatter[k] = albedo[size_t(k)];
    glass.scatter[3] = g;
    add_box(scene, {0, 0, 0}, 0.999f, m, false);
    return scene;
}

// glowing_box's black walls around a point light in a chromatic medium (g 0.6): the scene of
// single scattering, whose reference single_scattering() integrates.
struct PointLightInFog {
    std::array<float, 3> sigma{0.4f, 0.8f, 0.2f}, albedo{0.9f, 0.5f, 0.7f};
    float g = 0.6f, I = 2.f;
    D3 light{0.3, 0.4, -0.5};
    Scene scene() const;
    // single_scattering() in channel c, per unit ray direction.
    std::function<double(D3)> reference(int c) const;
};

// Light scattered once towards the camera at the origin along the unit direction d, through the
// medium inside glowing_box's black walls from a point light of intensity I at `light`:
// L = int_0^d sigma_s e^(-sigma_t t) p(cos) I / r^2 e^(-sigma_t r) dt, by Simpson's rule.
inline double single_scattering(D3 d, D3 light, double st, double ss, double g, double I) {
    double t_in, t_out;
    slab({0, 0, 0}, d, {0, 0, 0}, 1.0, &t_in, &t_out);
    const int n = 2000;
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
        const double t = t_out * i / n;
        const D3 to = light - t * d;
        const double r = length(to), cos_t = dot(d, to) / r;
        const double p = (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * cos_t, 1.5));
        const double f = ss * std::exp(-st * (t + r)) * p * I / (r * r);
        sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
    }
    return sum * t_out / (3 * n);
}

inline Scene PointLightInFog::scene() const {
    Scene s = glowing_box(0.f, 0.f);
    add_point_light(s, {float(light.x), float(light.y), float(light.z)}, I);
    set_medium(s, sigma, albedo, g);
    return s;
}

inline std::function<double(D3)> PointLightInFog::reference(int c) const {
    const double st = sigma[size_t(c)], ss = st * albedo[size_t(c)];
    return [=, *this](D3 d) { return single_scattering(d, light, st, ss, g, I); };
}

} // namespace clppm::test
