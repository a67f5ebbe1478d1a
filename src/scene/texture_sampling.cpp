#include "scene/texture_sampling.h"

#include <cmath>

namespace clppm {

namespace {

// Texel index along one axis: REPEAT wraps it into [0, size), MIRRORED_REPEAT reflects it at
// every edge, CLAMP_TO_EDGE clamps it.
long wrap_texel(long i, long size, bool clamp_to_edge, bool mirror) {
    if (clamp_to_edge) return i < 0 ? 0 : (i >= size ? size - 1 : i);
    if (mirror) {
        long m = i % (2 * size);
        if (m < 0) m += 2 * size;
        return m < size ? m : 2 * size - 1 - m;
    }
    long r = i % size;
    return r < 0 ? r + size : r;
}

// The coordinate reduced before scaling, as the kernel does: REPEAT keeps the fraction (only
// it matters), MIRRORED_REPEAT the position in its period of 2, CLAMP_TO_EDGE keeps [-1, 2]
// (beyond, every tap clamps to the edge alike).
double reduce(double u, bool clamp_to_edge, bool mirror) {
    if (!std::isfinite(u)) u = 0;
    if (clamp_to_edge) return std::fmin(2.0, std::fmax(-1.0, u));
    return mirror ? u - 2 * std::floor(u / 2) : u - std::floor(u);
}

} // namespace

dev::Texture plain_texture(uint32_t offset, uint32_t width, uint32_t height, uint32_t wrap) {
    dev::Texture t{};
    t.offset = offset, t.width = width, t.height = height, t.wrap = wrap;
    t.xform[0] = t.xform[4] = 1.f;
    return t;
}

std::array<double, 3> sample_texture(const Scene& scene, int index, double u0, double v0) {
    const dev::Texture& t = scene.textures[size_t(index)];
    const double u = t.xform[0] * u0 + double(t.xform[1]) * v0 + t.xform[2];
    const double v = t.xform[3] * u0 + double(t.xform[4]) * v0 + t.xform[5];
    const bool clamp_s = t.wrap & TEXTURE_CLAMP_S, clamp_t = t.wrap & TEXTURE_CLAMP_T;
    const bool mirror_s = t.wrap & TEXTURE_MIRROR_S, mirror_t = t.wrap & TEXTURE_MIRROR_T;
    const long w = long(t.width), h = long(t.height);
    const double rs = reduce(u, clamp_s, mirror_s), rt = reduce(v, clamp_t, mirror_t);
    if (t.wrap & TEXTURE_NEAREST) {
        const long px = wrap_texel(long(std::floor(rs * double(w))), w, clamp_s, mirror_s);
        const long py = wrap_texel(long(std::floor(rt * double(h))), h, clamp_t, mirror_t);
        const std::array<float, 4>& texel = scene.texels[t.offset + size_t(py) * size_t(w) + size_t(px)];
        return {texel[0], texel[1], texel[2]};
    }
    const double x = rs * double(w) - 0.5, y = rt * double(h) - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    std::array<double, 3> c{0, 0, 0};
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            const long px = wrap_texel(long(fx) + dx, w, clamp_s, mirror_s);
            const long py = wrap_texel(long(fy) + dy, h, clamp_t, mirror_t);
            const double weight = (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay);
            const std::array<float, 4>& texel = scene.texels[t.offset + size_t(py) * size_t(w) + size_t(px)];
            for (int k = 0; k < 3; ++k) c[size_t(k)] += weight * texel[size_t(k)];
        }
    return c;
}

} // namespace clppm
