#include "io/image_compare.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "util/error.h"

namespace clppm {

namespace {

bool finite_pixel(const Image& img, size_t p) {
    return std::isfinite(img.rgb[3 * p]) && std::isfinite(img.rgb[3 * p + 1]) && std::isfinite(img.rgb[3 * p + 2]);
}

double srgb(double v) {
    v = std::clamp(v, 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

} // namespace

ImageDifference compare_images(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw Error("cannot compare a " + std::to_string(a.width) + "x" + std::to_string(a.height) + " image with a " +
                    std::to_string(b.width) + "x" + std::to_string(b.height) + " one");
    ImageDifference d;
    d.pixels = size_t(a.width) * a.height;
    double se = 0, rel = 0, se_srgb = 0, sum_a = 0, sum_b = 0;
    size_t n = 0;
    for (size_t p = 0; p < d.pixels; ++p) {
        bool fa = finite_pixel(a, p), fb = finite_pixel(b, p);
        d.nonfinite_a += !fa, d.nonfinite_b += !fb;
        if (!fa || !fb) continue;
        for (int c = 0; c < 3; ++c) {
            double va = a.rgb[3 * p + c], vb = b.rgb[3 * p + c];
            se += (va - vb) * (va - vb);
            rel += (va - vb) * (va - vb) / (vb * vb + 1e-2);
            se_srgb += std::pow(srgb(va) - srgb(vb), 2);
            sum_a += va, sum_b += vb;
        }
        n += 3;
    }
    if (n > 0) {
        d.mean_a = sum_a / n, d.mean_b = sum_b / n;
        d.rel_mse = rel / n;
        d.rmse = std::sqrt(se / n);
        d.rel_rmse = d.mean_b > 0 ? d.rmse / d.mean_b : 0;
        d.rmse_srgb = std::sqrt(se_srgb / n);
    }
    // The relative luminance error per finite pixel, against 1% of the reference's mean
    // luminance where the reference is darker than that.
    auto luminance = [](const Image& im, size_t p) {
        return 0.2126 * im.rgb[3 * p] + 0.7152 * im.rgb[3 * p + 1] + 0.0722 * im.rgb[3 * p + 2];
    };
    double mean_y = 0;
    std::vector<double> rel_y;
    for (size_t p = 0; p < d.pixels; ++p)
        if (finite_pixel(a, p) && finite_pixel(b, p)) mean_y += std::max(0.0, luminance(b, p)), rel_y.push_back(0);
    if (!rel_y.empty()) {
        const double floor = 0.01 * mean_y / double(rel_y.size());
        size_t k = 0;
        for (size_t p = 0; p < d.pixels; ++p) {
            if (!finite_pixel(a, p) || !finite_pixel(b, p)) continue;
            const double denom = std::max(luminance(b, p), floor), diff = std::fabs(luminance(a, p) - luminance(b, p));
            rel_y[k++] = diff == 0 ? 0 : denom > 0 ? diff / denom : std::numeric_limits<double>::infinity();
        }
        const size_t rank = std::clamp<size_t>(size_t(std::ceil(0.9 * double(rel_y.size()))), 1, rel_y.size()) - 1;
        std::nth_element(rel_y.begin(), rel_y.begin() + rank, rel_y.end());
        d.p90_rel_error = rel_y[rank];
    }
    return d;
}

Image difference_image(const Image& a, const Image& b, double scale) {
    compare_images(a, b); // size check
    size_t n = size_t(a.width) * a.height;
    std::vector<double> diff(n, 0.0);
    for (size_t p = 0; p < n; ++p)
        for (int c = 0; c < 3; ++c) diff[p] += std::fabs(double(a.rgb[3 * p + c]) - b.rgb[3 * p + c]) / 3;
    if (!(scale > 0)) {
        std::vector<double> sorted;
        for (double v : diff)
            if (std::isfinite(v)) sorted.push_back(v);
        std::sort(sorted.begin(), sorted.end());
        scale = sorted.empty() ? 1 : std::max(1e-12, sorted[size_t(0.99 * (sorted.size() - 1))]);
    }
    // Black, blue, green, yellow, red at t = 0, 0.25, 0.5, 0.75, 1.
    static const float ramp[5][3] = {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
    Image out;
    out.width = a.width, out.height = a.height;
    out.rgb.resize(3 * n);
    for (size_t p = 0; p < n; ++p) {
        double t = std::isfinite(diff[p]) ? std::clamp(diff[p] / scale, 0.0, 1.0) * 4 : 4;
        int i = std::min(3, int(t));
        double f = t - i;
        for (int c = 0; c < 3; ++c) out.rgb[3 * p + c] = float(ramp[i][c] * (1 - f) + ramp[i + 1][c] * f);
        if (!finite_pixel(a, p) || !finite_pixel(b, p))
            out.rgb[3 * p] = 1, out.rgb[3 * p + 1] = 0, out.rgb[3 * p + 2] = 1;
    }
    return out;
}

Image box_filter(const Image& a, int k) {
    Image b;
    b.width = a.width / k;
    b.height = a.height / k;
    b.rgb.assign(size_t(b.width) * size_t(b.height) * 3, 0.f);
    for (int y = 0; y < b.height * k; ++y)
        for (int x = 0; x < b.width * k; ++x)
            for (int c = 0; c < 3; ++c)
                b.rgb[(size_t(y / k) * size_t(b.width) + size_t(x / k)) * 3 + size_t(c)] +=
                    a.rgb[(size_t(y) * size_t(a.width) + size_t(x)) * 3 + size_t(c)] / float(k * k);
    return b;
}

} // namespace clppm
