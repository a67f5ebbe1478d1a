// Octahedral unit vectors as kernels/sampling.cl packs them (2 x 16 bits), on the host, for tests
// that make photons and hit points by hand.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace clppm::test {

inline uint32_t oct(double x, double y, double z) {
    const double l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
    double px = x / l1, py = y / l1;
    if (z < 0) {
        const double ox = (1 - std::fabs(py)) * (px >= 0 ? 1 : -1), oy = (1 - std::fabs(px)) * (py >= 0 ? 1 : -1);
        px = ox, py = oy;
    }
    auto q = [](double v) { return uint32_t(std::lround(std::clamp((v * 0.5 + 0.5) * 65535, 0.0, 65535.0))); };
    return q(px) | (q(py) << 16);
}

// The unit vector e holds, in double.
inline void unoct(uint32_t e, double w[3]) {
    double x = double(e & 0xffffu) * (2.0 / 65535.0) - 1, y = double(e >> 16) * (2.0 / 65535.0) - 1;
    const double z = 1 - std::fabs(x) - std::fabs(y), t = std::max(-z, 0.0);
    x += x >= 0 ? -t : t;
    y += y >= 0 ? -t : t;
    const double l = std::sqrt(x * x + y * y + z * z);
    w[0] = x / l, w[1] = y / l, w[2] = z / l;
}

} // namespace clppm::test
