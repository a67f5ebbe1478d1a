#include "io/tone_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "io/image_io.h"

namespace clppm {

double tone_curve(ToneCurve curve, double x) {
    if (!(x > 0)) return 0; // also NaN
    switch (curve) {
    case ToneCurve::Clip: return std::min(x, 1.0);
    case ToneCurve::Aces: {
        // f(x) = x (a x + b) / (x (c x + d) + e): f' > 0 for x >= 0 since a d > b c; it passes 1
        // near x = 11 on its way to a / c = 1.033, and is clipped there.
        const double a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
        if (std::isinf(x)) return 1;
        return std::min(1.0, x * (a * x + b) / (x * (c * x + d) + e));
    }
    case ToneCurve::Reinhard: return std::isinf(x) ? 1.0 : x / (1 + x);
    }
    return 0;
}

double auto_exposure_ev(const Image& img) {
    double sum_log = 0;
    size_t n = 0;
    for (size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
        const double l = 0.2126 * img.rgb[i] + 0.7152 * img.rgb[i + 1] + 0.0722 * img.rgb[i + 2];
        if (!std::isfinite(l) || !(l > 0)) continue;
        sum_log += std::log(l);
        ++n;
    }
    if (n == 0) return 0; // nothing but black
    return std::clamp(std::log2(0.18) - sum_log / (double(n) * std::log(2.0)), -64.0, 64.0);
}

double applied_exposure_ev(const ToneMapping& tm, const Image& img) {
    return tm.exposure_ev + (tm.auto_exposure ? auto_exposure_ev(img) : 0.0);
}

} // namespace clppm
