#include "scene/studio_environment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "scene/environment.h"

namespace clppm {

namespace {

struct Lobe {
    double dir[3]; // unit direction the light comes from
    double width;  // in 1 - cos(angle): the lobe falls to 1/e at this distance from its axis
    double rgb[3]; // peak radiance
};

// A warm key light high on the camera's left, in front of the model; a cool, weaker rim light
// behind it on the right; both broad (about 25 and 35 degrees), so that highlights are soft.
const Lobe kLobes[] = {
    {{-0.48, 0.70, 0.53}, 0.09, {9.0, 8.6, 8.0}},
    {{0.62, 0.35, -0.70}, 0.18, {2.4, 2.6, 3.0}},
};

double unit_dot(const double a[3], double x, double y, double z) {
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return (a[0] * x + a[1] * y + a[2] * z) / n;
}

} // namespace

double studio_radiance_unscaled(double x, double y, double z, int channel) {
    // Ground 0.25, horizon 0.55, zenith 0.85: a smooth step over the horizon, as a cyclorama.
    const double t = std::clamp(0.5 + y * 2.0, 0.0, 1.0), step = t * t * (3 - 2 * t);
    double L = 0.25 + 0.3 * step + 0.3 * std::max(0.0, y);
    for (const Lobe& l : kLobes) L += l.rgb[channel] * std::exp((unit_dot(l.dir, x, y, z) - 1.0) / l.width);
    return L;
}

Image studio_environment(int width, int height) {
    Image img;
    img.width = width, img.height = height;
    img.rgb.assign(size_t(width) * size_t(height) * 3, 0.f);
    // Each texel: the mean of 4 x 4 samples over it; then the irradiance on an upward surface,
    // integrated over the same texels, sets the scale.
    constexpr int kSub = 4;
    std::vector<double> texel(img.rgb.size());
    double irradiance_up = 0; // mean over RGB
    for (int j = 0; j < height; ++j) {
        // The row's solid angle per texel and its mean cos(theta) from +Y (exact for the row).
        const double c0 = std::cos(j * M_PI / height), c1 = std::cos((j + 1) * M_PI / height);
        const double omega = 2 * M_PI / width * (c0 - c1), mean_cos = 0.5 * (c0 + c1);
        for (int i = 0; i < width; ++i) {
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int sj = 0; sj < kSub; ++sj)
                    for (int si = 0; si < kSub; ++si) {
                        const std::array<double, 3> d =
                            env_direction((i + (si + 0.5) / kSub) / width, (j + (sj + 0.5) / kSub) / height);
                        sum += studio_radiance_unscaled(d[0], d[1], d[2], c);
                    }
                const double L = sum / (kSub * kSub);
                texel[(size_t(j) * size_t(width) + size_t(i)) * 3 + size_t(c)] = L;
                if (mean_cos > 0) irradiance_up += L * mean_cos * omega / 3;
            }
        }
    }
    const double scale = M_PI / irradiance_up;
    for (size_t k = 0; k < texel.size(); ++k) img.rgb[k] = float(texel[k] * scale);
    return img;
}

} // namespace clppm
