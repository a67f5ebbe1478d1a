#include "integrators/error_estimate.h"

#include <algorithm>
#include <cmath>

#include "device/kernel_launch.h"
#include "util/error.h"

namespace clppm {

namespace {

// The regularised incomplete beta function I_x(a, b) by its continued fraction (modified Lentz),
// on the side where it converges fast.
double incomplete_beta(double a, double b, double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    if (x > (a + 1) / (a + b + 2)) return 1 - incomplete_beta(b, a, 1 - x);
    const double front =
        std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x)) / a;
    const double tiny = 1e-300;
    double f = 1, c = 1, d = 0;
    for (int i = 0; i <= 400; ++i) {
        const int m = i / 2;
        double num;
        if (i == 0) num = 1;
        else if (i % 2 == 0) num = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
        else num = -((a + m) * (a + b + m) * x) / ((a + 2 * m) * (a + 2 * m + 1));
        d = 1 + num * d;
        if (std::fabs(d) < tiny) d = tiny;
        d = 1 / d;
        c = 1 + num / c;
        if (std::fabs(c) < tiny) c = tiny;
        const double cd = c * d;
        f *= cd;
        if (std::fabs(1 - cd) < 1e-15) break;
    }
    return front * (f - 1);
}

double student_t_cdf(double t, double nu) {
    if (std::isinf(nu)) return 0.5 * std::erfc(-t / std::sqrt(2.0));
    const double tail = 0.5 * incomplete_beta(0.5 * nu, 0.5, nu / (nu + t * t));
    return t >= 0 ? 1 - tail : tail;
}

// The path tracer's samples are heavy-tailed (a rare path to a small bright light or through
// rough glass carries much of a pixel's value), so a pixel that has not met such a path yet
// underestimates its variance (and its mean) with high probability: against Mitsuba on a rough
// glass block, sigma alone stopped at 1.15 times the target after 196 passes. Its neighbours
// have likely met one: each pixel takes the larger of its own relative variance and the mean over
// its 3 x 3 neighbourhood, which nine times the samples make far less likely to have missed it.
void pool_path_traced_sigma(ErrorImage& e, double t) {
    const int w = e.width, h = e.height;
    if (w <= 0 || h <= 0) return;
    double mean = 0;
    for (float l : e.luminance) mean += std::max(0.0, double(l));
    const double floor = kRelativeFloor * mean / double(e.luminance.size());
    std::vector<double> v(e.sigma.size());
    for (size_t i = 0; i < v.size(); ++i) {
        const double d = std::max(double(e.luminance[i]), floor);
        v[i] = d > 0 ? double(e.sigma[i]) * double(e.sigma[i]) / (d * d) : 0.0;
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            int n = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
                    sum += v[size_t(yy) * size_t(w) + size_t(xx)];
                    ++n;
                }
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const double pooled = sum / n;
            if (!(pooled > v[i])) continue; // also keeps +Inf and NaN as they are
            const double d = std::max(double(e.luminance[i]), floor);
            e.sigma[i] = float(d * std::sqrt(pooled));
            e.noise[i] = float(t * double(e.sigma[i]));
            e.absolute[i] = std::fabs(e.bias[i]) + e.noise[i];
        }
}

// The variance of a pixel's mean over Sobol' passes as a fraction g of what independent passes'
// spread says (kernels/pt_error.cl). At the last power-of-two count P each pixel's half-split D_i
// estimates Var(mean) times 2^a - 1, where the variance falls as P^-a (a = 1 for independent
// passes); pooled over the pixels, relative to their luminance as the measure is, against
// sigma_i^2 n / P, it is G(P) = (2^a - 1) g(P). Since g(P) ~ P^(1 - a), G(P) / G(P/2) = 2^(1-a)
// gives a, clamped to [1, 2]. Between powers of two g(P) is kept: conservative, as the error still
// falls. `raw` remembers G by P across calls; returns 1 (no gain) before P = 2.
double sobol_gain(const std::vector<cl_float8>& b, uint64_t passes, double floor, std::map<uint64_t, double>& raw) {
    if (passes < 2) return 1;
    uint64_t p = 1;
    while (p * 2 <= passes) p *= 2;
    double num = 0, den = 0;
    for (const cl_float8& v : b) {
        const double d = std::max(double(v.s[1]), floor), sigma = v.s[5], split = v.s[6];
        if (!(d > 0) || !(split >= 0) || !std::isfinite(sigma) || !std::isfinite(split)) continue;
        num += split / (d * d);
        den += sigma * sigma * double(passes) / double(p) / (d * d);
    }
    if (!(den > 0)) return 1;
    const double g_raw = num / den;
    raw[p] = g_raw;
    double a = 1;
    if (auto it = raw.find(p / 2); it != raw.end() && it->second > 0 && g_raw > 0)
        a = std::clamp(1 - std::log2(g_raw / it->second), 1.0, 2.0);
    return std::clamp(g_raw / (std::exp2(a) - 1), 0.0, 1.0);
}

} // namespace

double student_t_quantile(double p, double nu) {
    if (!(p > 0 && p < 1) || !(nu > 0)) throw Error("student_t_quantile: p must be in (0, 1) and nu > 0");
    if (p < 0.5) return -student_t_quantile(1 - p, nu);
    // The CDF is monotone: bracket, then bisect to the last bit.
    double lo = 0, hi = 1;
    while (student_t_cdf(hi, nu) < p && hi < 1e300) lo = hi, hi *= 2;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (student_t_cdf(mid, nu) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double normal_quantile(double p) { return student_t_quantile(p, std::numeric_limits<double>::infinity()); }

double confidence_multiplier(double confidence, uint64_t n) {
    if (n < 2) return std::numeric_limits<double>::infinity();
    return student_t_quantile(0.5 * (1 + confidence), double(n - 1));
}

std::vector<float> relative_bounds(const std::vector<float>& absolute, const std::vector<float>& luminance) {
    double mean = 0;
    for (float l : luminance) mean += std::max(0.0, double(l));
    mean = luminance.empty() ? 0 : mean / double(luminance.size());
    const double floor = kRelativeFloor * mean;
    std::vector<float> rel(absolute.size());
    for (size_t i = 0; i < absolute.size(); ++i) {
        const double denom = std::max(double(luminance[i]), floor);
        const double e = absolute[i];
        rel[i] = e == 0 ? 0.f : denom > 0 ? float(e / denom) : std::numeric_limits<float>::infinity();
    }
    return rel;
}

double expected_image_error(const std::vector<float>& sigma, const std::vector<float>& bias,
                            const std::vector<float>& luminance, double percentile) {
    const size_t n = sigma.size();
    if (n == 0) return std::numeric_limits<double>::infinity();
    double mean = 0;
    for (float l : luminance) mean += std::max(0.0, double(l));
    const double floor = kRelativeFloor * mean / double(n);
    // At most kMaxPixels pixels, evenly strided: the quantile of a mixture is a smooth function
    // of it, and the bisection below evaluates every pixel ~60 times.
    constexpr size_t kMaxPixels = 1u << 14;
    const size_t stride = (n + kMaxPixels - 1) / kMaxPixels;
    std::vector<double> s, b; // per pixel, relative to its denominator
    for (size_t i = 0; i < n; i += stride) {
        const double d = std::max(double(luminance[i]), floor);
        if (!(d > 0)) return std::numeric_limits<double>::infinity();
        s.push_back(double(sigma[i]) / d);
        b.push_back(bias.empty() ? 0.0 : double(bias[i]) / d);
        if (std::isnan(s.back()) || std::isnan(b.back())) return std::numeric_limits<double>::infinity();
    }
    // P(|b + s Z| > q) for Z ~ N(0, 1); s = +Inf: 1; s = 0: the bias alone.
    auto exceed = [](double q, double bi, double si) {
        if (std::isinf(si)) return 1.0;
        if (si == 0) return std::fabs(bi) > q ? 1.0 : 0.0;
        const double k = 1.0 / (si * std::sqrt(2.0));
        return 0.5 * std::erfc((q - bi) * k) + 0.5 * std::erfc((q + bi) * k);
    };
    const double tail = 1 - percentile;
    auto tail_at = [&](double q) {
        double sum = 0;
        for (size_t i = 0; i < s.size(); ++i) sum += exceed(q, b[i], s[i]);
        return sum / double(s.size());
    };
    // The fraction of pixels above q falls from 1 to 0 as q grows: bracket, then bisect in log q.
    double hi = 1;
    while (tail_at(hi) > tail) {
        hi *= 4;
        if (hi > 1e30) return std::numeric_limits<double>::infinity();
    }
    double lo = hi / 4;
    while (lo > 1e-30 && tail_at(lo) <= tail) lo /= 4;
    for (int it = 0; it < 40 && hi > lo * (1 + 1e-4); ++it) {
        const double mid = std::sqrt(lo * hi);
        (tail_at(mid) > tail ? lo : hi) = mid;
    }
    return hi;
}

double c4(uint64_t n) {
    if (n < 2) return 0;
    const double m = double(n);
    return std::sqrt(2 / (m - 1)) * std::exp(std::lgamma(m / 2) - std::lgamma((m - 1) / 2));
}

double image_error(std::vector<float> v, double percentile) {
    if (v.empty()) return std::numeric_limits<double>::infinity();
    for (float& x : v)
        if (std::isnan(x)) x = std::numeric_limits<float>::infinity();
    const size_t rank = size_t(std::ceil(percentile * double(v.size())));
    auto it = v.begin() + std::clamp<size_t>(rank, 1, v.size()) - 1;
    std::nth_element(v.begin(), it, v.end());
    return double(*it);
}

ErrorEstimator::ErrorEstimator(const DeviceContext& dc, const cl::Program& program, uint32_t num_pixels,
                               IntegratorStats& stats, const PixelHitpoints& layout)
    : dc_(dc), stats_(stats), n_(num_pixels), layout_(layout) {
    if (!layout_.path_traced) k_gather_ = cl::Kernel(program, "error_gather");
    k_reset_ = cl::Kernel(program, layout_.path_traced ? "pt_error_reset" : "error_reset");
    k_update_ = cl::Kernel(program, layout_.path_traced ? "pt_error_update" : "error_update");
    k_bound_ = cl::Kernel(program, layout_.path_traced ? "pt_error_bound" : "error_bound");
    auto make = [&](size_t bytes) {
        stats_.device_bytes += bytes;
        return make_buffer(dc_.context, CL_MEM_READ_WRITE, std::max<size_t>(bytes, 1));
    };
    if (!layout_.path_traced)
        laplacian_ = make(size_t(layout_.num_hitpoints ? layout_.num_hitpoints : n_) * sizeof(cl_long));
    error_stats_ = make(size_t(n_) * sizeof(dev::ErrorStats));
    bound_ = make(size_t(n_) * sizeof(cl_float8));
}

void ErrorEstimator::reset(const cl::Buffer& source) {
    if (layout_.path_traced) set_args(k_reset_, 0, source, cl_uint(n_), error_stats_);
    else set_args(k_reset_, 0, source, layout_.pixel_first, cl_uint(n_), error_stats_);
    enqueue_1d(dc_.queue, k_reset_, n_);
    passes_ = 0;
    sobol_raw_gain_.clear();
}

void ErrorEstimator::update_accum(const cl::Buffer& accum, uint32_t first, uint32_t count) {
    set_args(k_update_, 0, accum, cl_uint(first + count), error_stats_);
    cl::Event ev;
    enqueue_1d_range(dc_.queue, k_update_, first, count, &ev);
    add_event_time(stats_, "error_estimate", ev);
    ++passes_;
}

void ErrorEstimator::update(const cl::Buffer& passflux, const cl::Buffer& hitpoints, const cl::Buffer& hit_stats,
                            double global_r2, double power_per_photon) {
    set_args(k_update_, 0, passflux, laplacian_, hitpoints, hit_stats, layout_.pixel_first, layout_.emitted,
             cl_uint(n_), cl_uint(layout_.spp), cl_double(global_r2), cl_double(power_per_photon), error_stats_);
    cl::Event ev;
    enqueue_1d(dc_.queue, k_update_, n_, &ev);
    add_event_time(stats_, "error_estimate", ev);
    ++passes_;
}

ErrorImage ErrorEstimator::estimate(double confidence, int width, int height, const std::vector<float>* min_sigma,
                                    double scale_variance) {
    if (!(confidence > 0 && confidence < 1)) throw Error("error estimate: the confidence must be in (0, 1)");
    const double t = confidence_multiplier(confidence, passes_);
    set_args(k_bound_, 0, error_stats_, cl_uint(n_), cl_double(t), bound_);
    enqueue_1d(dc_.queue, k_bound_, n_);
    std::vector<cl_float8> b = read_buffer<cl_float8>(dc_.queue, bound_, n_);
    ErrorImage e;
    e.width = width, e.height = height, e.passes = passes_;
    for (auto* v : {&e.absolute, &e.luminance, &e.bias, &e.noise, &e.bias_clean, &e.sigma, &e.bias_sigma})
        v->resize(n_);
    for (uint32_t i = 0; i < n_; ++i) {
        e.absolute[i] = b[i].s[0];
        e.luminance[i] = b[i].s[1];
        e.bias[i] = b[i].s[2];
        e.noise[i] = b[i].s[3];
        e.bias_clean[i] = b[i].s[4];
        e.sigma[i] = b[i].s[5];
        e.bias_sigma[i] = layout_.path_traced ? 0.0f : b[i].s[6]; // pt_error_bound keeps other data there
        if (min_sigma && (*min_sigma)[i] > e.sigma[i]) {
            e.sigma[i] = (*min_sigma)[i];
            e.noise[i] = float(t * double(e.sigma[i]));
            e.absolute[i] = std::fabs(e.bias[i]) + e.noise[i];
        }
        if (scale_variance > 0) {
            const double l = e.luminance[i];
            e.sigma[i] = float(std::sqrt(double(e.sigma[i]) * e.sigma[i] + scale_variance * l * l));
            e.noise[i] = float(t * double(e.sigma[i]));
            e.absolute[i] = std::fabs(e.bias[i]) + e.noise[i];
        }
    }
    if (layout_.path_traced) {
        double mean = 0;
        for (float l : e.luminance) mean += std::max(0.0, double(l));
        const double gain =
            layout_.sobol ? sobol_gain(b, passes_, kRelativeFloor * mean / double(n_), sobol_raw_gain_) : 1.0;
        pool_path_traced_sigma(e, t);
        if (gain < 1) {
            const double s = std::sqrt(gain);
            for (uint32_t i = 0; i < n_; ++i) {
                e.sigma[i] = float(e.sigma[i] * s);
                e.noise[i] = float(e.noise[i] * s);
                e.absolute[i] = e.noise[i];
            }
        }
    }
    e.relative = relative_bounds(e.absolute, e.luminance);
    e.image_error = image_error(e.relative);
    const double calibration = layout_.path_traced ? kErrorCalibration : kPhotonErrorCalibration;
    if (passes_ >= 2) {
        std::vector<float> sigma = e.sigma;
        const double k = 1 / c4(passes_);
        for (float& s : sigma) s = float(s * k);
        e.expected_error = calibration * expected_image_error(sigma, e.bias_clean, e.luminance);
    }
    if (min_sigma) e.sample_floor = calibration * expected_image_error(*min_sigma, {}, e.luminance);
    return e;
}

std::vector<dev::ErrorStats> ErrorEstimator::read() const {
    return read_buffer<dev::ErrorStats>(dc_.queue, error_stats_, n_);
}

void ErrorEstimator::write(const std::vector<dev::ErrorStats>& v) {
    write_buffer(dc_.queue, error_stats_, v);
    passes_ = v.empty() ? 0 : uint64_t(v[0].n);
}

void ErrorTrend::add(uint64_t pass, double seconds, double error) {
    if (std::isfinite(error) && error > 0) points_.push_back({double(pass), seconds, error});
}

double ErrorTrend::eta_seconds(double target) const {
    if (points_.empty()) return -1;
    if (points_.back().error <= target) return 0;
    // The recent half of the history (at most 64 points): the early passes decay differently.
    const size_t count = std::min<size_t>(64, (points_.size() + 1) / 2);
    if (count < 4) return -1;
    const size_t first = points_.size() - count;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = first; i < points_.size(); ++i) {
        const double x = std::log(points_[i].pass), y = std::log(points_[i].error);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double nn = double(count), den = nn * sxx - sx * sx;
    if (!(den > 0)) return -1;
    const double slope = (nn * sxy - sx * sy) / den, icpt = (sy - slope * sx) / nn;
    if (!(slope < 0)) return -1;
    const Point &p0 = points_[first], &p1 = points_.back();
    if (!(p1.pass > p0.pass)) return -1;
    const double seconds_per_pass = (p1.seconds - p0.seconds) / (p1.pass - p0.pass);
    const double pass_needed = std::exp((std::log(target) - icpt) / slope);
    if (!std::isfinite(pass_needed)) return -1;
    return std::max(0.0, pass_needed - p1.pass) * seconds_per_pass;
}

Image false_colour(const std::vector<float>& v, int width, int height, double scale) {
    static const float kRamp[5][3] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
    Image img;
    img.width = width, img.height = height;
    img.rgb.resize(size_t(width) * height * 3);
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        float* c = &img.rgb[3 * i];
        if (!std::isfinite(v[i])) {
            c[0] = 1, c[1] = 0, c[2] = 1;
            continue;
        }
        const double t = std::clamp(double(v[i]) / scale, 0.0, 1.0) * 4.0;
        const int k = std::min(3, int(t));
        const float f = float(t - k);
        for (int q = 0; q < 3; ++q) c[q] = kRamp[k][q] + f * (kRamp[k + 1][q] - kRamp[k][q]);
    }
    return img;
}

} // namespace clppm
