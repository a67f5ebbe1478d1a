#include "io/image_compare.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "io/stats_json.h"
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

std::string compare_usage() {
    return "Usage: clppm compare IMAGE.exr REFERENCE.exr [--diff OUT.png] [--box K]\n"
           "Prints, as JSON, how far IMAGE is from REFERENCE: both means and their ratio, the relative MSE\n"
           "(per pixel and channel, (a - b)^2 / (b^2 + 0.01)), RMSE, relative RMSE, the RMSE of the sRGB\n"
           "codes, p90_rel_error (the 90th percentile over pixels of |Y_a - Y_b| / max(Y_b, 1% of the mean Y_b)\n"
           "on luminance: the measure --target-error states) and NaN/Inf counts.\n\n"
           "  --diff OUT.png   also write a false-colour difference image\n"
           "  --box K          also the relative MSE of both images box-filtered over K x K pixels\n"
           "                   (box_rel_mse: bias more than noise); K in 1..1024\n"
           "  -h, --help       print this help and exit\n";
}

int compare_command(int argc, char** argv) {
    const char* usage = " (usage: clppm compare A.exr REFERENCE.exr [--diff OUT.png] [--box K])";
    std::vector<std::string> files;
    std::string diff_png;
    int box = 0;
    for (int i = 0; i < argc; ++i) {
        std::string s = argv[i];
        if (s == "--help" || s == "-h") {
            std::fputs(compare_usage().c_str(), stdout);
            return 0;
        }
        if (s == "--diff") {
            if (i + 1 >= argc) throw Error("compare --diff: missing value OUT.png");
            diff_png = argv[++i];
            const size_t n = diff_png.size();
            std::string tail = n >= 4 ? diff_png.substr(n - 4) : "";
            for (char& ch : tail) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
            if (n <= 4 || tail != ".png")
                throw Error("compare --diff " + diff_png +
                            ": must be a file name ending in .png (it is written as PNG)");
        } else if (s == "--box") {
            const std::string v = i + 1 < argc ? argv[++i] : "";
            char* end = nullptr;
            const long k = std::strtol(v.c_str(), &end, 10);
            if (v.empty() || *end != '\0' || k < 1 || k > 1024)
                throw Error("compare --box " + (v.empty() ? std::string("''") : v) + ": must be an integer in 1..1024");
            box = int(k);
        } else if (s.rfind("--", 0) == 0) {
            throw Error("compare: unknown option " + s + usage);
        } else {
            files.push_back(s);
        }
    }
    if (files.size() != 2) throw Error(std::string("compare: expected two EXR files") + usage);
    Image a = read_exr(files[0]), b = read_exr(files[1]);
    ImageDifference d = compare_images(a, b);
    if (box > 0 && (a.width < box || a.height < box))
        throw Error("compare --box " + std::to_string(box) + ": larger than the images");
    if (!diff_png.empty()) write_png(diff_png, difference_image(a, b));
    Json j;
    j["image"] = files[0];
    j["reference"] = files[1];
    j["pixels"] = d.pixels;
    j["nonfinite_image"] = d.nonfinite_a;
    j["nonfinite_reference"] = d.nonfinite_b;
    j["mean_image"] = d.mean_a;
    j["mean_reference"] = d.mean_b;
    j["mean_ratio"] = d.mean_b > 0 ? d.mean_a / d.mean_b : 0.0;
    j["rel_mse"] = d.rel_mse;
    j["rmse"] = d.rmse;
    j["rel_rmse"] = d.rel_rmse;
    j["rmse_srgb"] = d.rmse_srgb;
    j["p90_rel_error"] = d.p90_rel_error;
    if (box > 0) {
        j["box"] = box;
        j["box_rel_mse"] = compare_images(box_filter(a, box), box_filter(b, box)).rel_mse;
    }
    std::fputs(to_json_text(j).c_str(), stdout);
    return 0;
}

} // namespace clppm
