#include "scene/light_power.h"

#include <algorithm>
#include <cmath>

#include "scene/texture_sampling.h"

namespace clppm {

namespace {

constexpr double kPi = 3.14159265358979323846;

} // namespace

double punctual_light_power(const dev::Light& l, double scene_radius) {
    const double i = (double(l.radiance[0]) + l.radiance[1] + l.radiance[2]) / 3.0;
    switch (l.type) {
    case LIGHT_POINT: return 4 * kPi * i;
    case LIGHT_SPOT: return 2 * kPi * i * ((1 - double(l.cos_inner)) + (double(l.cos_inner) - l.cos_outer) / 3);
    case LIGHT_DIRECTIONAL: return i * kPi * scene_radius * scene_radius;
    default: return 0;
    }
}

double textured_emission_mean(const Scene& scene, size_t tri) {
    const dev::TriShading& sh = scene.shading[tri];
    const dev::Material& m = scene.materials[sh.material];
    const dev::Texture& t = scene.textures[size_t(m.emissive_tex)];
    double uv[3][2] = {{sh.uv0[0], sh.uv0[1]}, {sh.uv1[0], sh.uv1[1]}, {sh.uv2[0], sh.uv2[1]}};
    if (t.texcoord == 1 && !scene.uv1.empty())
        for (int k = 0; k < 3; ++k)
            uv[k][0] = scene.uv1[3 * tri + size_t(k)][0], uv[k][1] = scene.uv1[3 * tri + size_t(k)][1];
    double longest = 0; // in texels
    for (int k = 0; k < 3; ++k) {
        const double* a = uv[k];
        const double* b = uv[(k + 1) % 3];
        const double du = (b[0] - a[0]) * t.width, dv = (b[1] - a[1]) * t.height;
        longest = std::max(longest, std::sqrt(du * du + dv * dv));
    }
    const int n = std::isfinite(longest) ? std::clamp(int(std::ceil(2 * longest)), 2, 64) : 64;
    // Sub-triangle centroids: the upward ones at ((i + 1/3), (j + 1/3)) / n, the downward ones at
    // ((i + 2/3), (j + 2/3)) / n, in the (b1, b2) barycentric square's lower half.
    double sum = 0;
    int count = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i + j < n; ++i)
            for (int down = 0; down < 2; ++down) {
                if (down && i + j + 1 >= n) continue;
                const double b1 = (i + (down ? 2.0 : 1.0) / 3) / n, b2 = (j + (down ? 2.0 : 1.0) / 3) / n;
                const double b0 = 1 - b1 - b2;
                const std::array<double, 3> c =
                    sample_texture(scene, m.emissive_tex, b0 * uv[0][0] + b1 * uv[1][0] + b2 * uv[2][0],
                                   b0 * uv[0][1] + b1 * uv[1][1] + b2 * uv[2][1]);
                sum += (m.emission[0] * c[0] + m.emission[1] * c[1] + m.emission[2] * c[2]) / 3;
                ++count;
            }
    return sum / count;
}

} // namespace clppm
