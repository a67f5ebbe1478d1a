#include "scene/texture_sampling.h"

#include <cmath>

namespace clppm {

namespace {

// Texel index along one axis: REPEAT wraps it into [0, size), CLAMP_TO_EDGE clamps it.
long wrap_texel(long i, long size, bool clamp_to_edge) {
    if (clamp_to_edge) return i < 0 ? 0 : (i >= size ? size - 1 : i);
    long r = i % size;
    return r < 0 ? r + size : r;
}

// The coordinate reduced before scaling, as the kernel does: REPEAT keeps the fraction (only
// it matters), CLAMP_TO_EDGE keeps [-1, 2] (beyond, every tap clamps to the edge alike).
double reduce(double u, bool clamp_to_edge) {
    if (!std::isfinite(u)) u = 0;
    return clamp_to_edge ? std::fmin(2.0, std::fmax(-1.0, u)) : u - std::floor(u);
}

} // namespace

std::array<double, 3> sample_texture(const Scene& scene, int index, double u, double v) {
    const dev::Texture& t = scene.textures[size_t(index)];
    const bool clamp_s = t.wrap & 1u, clamp_t = t.wrap & 2u;
    const long w = long(t.width), h = long(t.height);
    const double x = reduce(u, clamp_s) * double(w) - 0.5, y = reduce(v, clamp_t) * double(h) - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    std::array<double, 3> c{0, 0, 0};
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            const long px = wrap_texel(long(fx) + dx, w, clamp_s), py = wrap_texel(long(fy) + dy, h, clamp_t);
            const double weight = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay);
            const std::array<float, 4>& texel = scene.texels[t.offset + size_t(py) * size_t(w) + size_t(px)];
            for (int k = 0; k < 3; ++k) c[size_t(k)] += weight * texel[size_t(k)];
        }
    return c;
}

} // namespace clppm
