// Statistical helpers for the sampling tests: the regularized incomplete gamma function, Pearson's
// chi-square test with pooling of sparse cells (as pbrt-v4's chi2test and Mitsuba's ChiSquareTest
// do), 2-D Gauss-Legendre integration of a pdf over bins, and a few moments. No dependencies
// beyond <cmath>; everything in double.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

namespace clppm::test {

// Vigna's SplitMix64 step, the host reference for kernels/rng.cl's splitmix64 (the rng and Sobol'
// tests derive their streams' seeds with it).
inline uint64_t ref_splitmix64(uint64_t x) {
    uint64_t z = x + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// P(a, x) = gamma(a, x) / Gamma(a) by its series, valid for x < a + 1 (Numerical Recipes 6.2.5).
inline double gamma_p_series(double a, double x) {
    double ap = a, sum = 1.0 / a, del = sum;
    for (int n = 0; n < 100000; ++n) {
        ap += 1.0;
        del *= x / ap;
        sum += del;
        if (std::fabs(del) < std::fabs(sum) * 1e-16) break;
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) = Gamma(a, x) / Gamma(a) by its continued fraction (modified Lentz), for x >= a + 1.
inline double gamma_q_fraction(double a, double x) {
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (std::fabs(del - 1.0) < 1e-16) break;
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

// The regularized upper incomplete gamma function Q(a, x) = 1 - P(a, x).
inline double gamma_q(double a, double x) {
    if (x <= 0.0) return 1.0;
    if (x < a + 1.0) return 1.0 - gamma_p_series(a, x);
    return gamma_q_fraction(a, x);
}

// P(X >= chi2) for X ~ chi-square with dof degrees of freedom.
inline double chi2_p_value(double chi2, int dof) { return dof <= 0 ? 1.0 : gamma_q(0.5 * dof, 0.5 * chi2); }

// Significance for each of `tests` tests so that the chance of any false alarm is `alpha`
// (Sidak correction, as pbrt-v4's chi2test uses).
inline double sidak(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / tests); }

struct Chi2Result {
    double chi2 = 0;
    int dof = 0;
    double p_value = 0;
    std::string error; // non-empty: a sample fell where the expected frequency is zero
};

// Pearson's chi-square of observed against expected counts. Cells expecting fewer than
// min_expected samples are pooled into one cell (merged with the next-smallest cells until the
// pool reaches min_expected), so that the chi-square approximation holds. A cell with essentially
// zero expectation but observed samples fails outright: the sampler puts mass where the pdf is 0.
inline Chi2Result chi2_test(const std::vector<double>& observed, const std::vector<double>& expected,
                            double min_expected = 5.0) {
    Chi2Result r;
    const double total = std::accumulate(expected.begin(), expected.end(), 0.0);
    std::vector<size_t> order(observed.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    double pool_obs = 0, pool_exp = 0;
    int cells = 0;
    for (size_t k = 0; k < order.size(); ++k) {
        size_t i = order[k];
        if (expected[i] <= 1e-9 * total && observed[i] > 0) {
            r.error = "cell " + std::to_string(i) + " expects " + std::to_string(expected[i]) + " samples but got " +
                      std::to_string(observed[i]);
            r.p_value = 0;
            return r;
        }
        if (expected[i] < min_expected || (pool_exp > 0 && pool_exp < min_expected)) {
            pool_obs += observed[i];
            pool_exp += expected[i];
            continue;
        }
        double d = observed[i] - expected[i];
        r.chi2 += d * d / expected[i];
        ++cells;
    }
    if (pool_exp > 0) {
        double d = pool_obs - pool_exp;
        r.chi2 += d * d / pool_exp;
        ++cells;
    } else if (pool_obs > 0) {
        r.error = "samples in cells of zero expectation";
        return r;
    }
    r.dof = cells - 1;
    r.p_value = chi2_p_value(r.chi2, r.dof);
    return r;
}

// Integral of f(x, y) over [x0,x1] x [y0,y1]: composite 4-point Gauss-Legendre on n x n cells.
// An open rule, so a pdf that jumps on a bin edge (a cone's rim, a hemisphere's horizon) is
// integrated exactly where a closed rule (Simpson) would smear the jump into the neighbour bin.
inline double integrate_2d(const std::function<double(double, double)>& f, double x0, double x1, double y0, double y1,
                           int n = 4) {
    static const double node[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    static const double weight[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    const double hx = (x1 - x0) / n, hy = (y1 - y0) / n;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    sum += weight[a] * weight[b] *
                           f(x0 + hx * (i + 0.5 + 0.5 * node[a]), y0 + hy * (j + 0.5 + 0.5 * node[b]));
    return sum * hx * hy / 4.0;
}

// Bins over the sphere of directions in (cos theta, phi) about an axis, as pbrt-v4 and Mitsuba
// bin their warping tests: equal steps in cos theta are equal solid angles.
struct SphereBins {
    int n_cos = 10, n_phi = 20;
    double cos_lo = -1, cos_hi = 1; // the cos theta range binned; outside it: no bin (-1)
    int size() const { return n_cos * n_phi; }
    int index(double cos_t, double phi) const {
        if (!(cos_t >= cos_lo && cos_t <= cos_hi)) return -1;
        int i = std::min(n_cos - 1, int((cos_t - cos_lo) / (cos_hi - cos_lo) * n_cos));
        double u = phi / (2 * M_PI);
        u -= std::floor(u);
        int j = std::min(n_phi - 1, int(u * n_phi));
        return i * n_phi + j;
    }
    // Expected counts for n samples of a pdf over solid angle, pdf(cos theta, phi): the pdf
    // integrated over each bin (d omega = d cos theta d phi).
    std::vector<double> expected(const std::function<double(double, double)>& pdf, double n, int sub = 4) const {
        std::vector<double> e(size());
        const double dc = (cos_hi - cos_lo) / n_cos, dp = 2 * M_PI / n_phi;
        for (int i = 0; i < n_cos; ++i)
            for (int j = 0; j < n_phi; ++j)
                e[i * n_phi + j] =
                    n * integrate_2d(pdf, cos_lo + i * dc, cos_lo + (i + 1) * dc, j * dp, (j + 1) * dp, sub);
        return e;
    }
};

// Pearson correlation of two equally long sequences.
inline double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    const size_t n = a.size();
    double ma = 0, mb = 0;
    for (size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
    ma /= n, mb /= n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / std::sqrt(saa * sbb);
}

// Mean and standard error of the mean.
struct MeanSe {
    double mean = 0, se = 0;
};
inline MeanSe mean_se(const std::vector<double>& v) {
    MeanSe m;
    const double n = double(v.size());
    for (double x : v) m.mean += x;
    m.mean /= n;
    double var = 0;
    for (double x : v) var += (x - m.mean) * (x - m.mean);
    m.se = std::sqrt(var / (n - 1) / n);
    return m;
}

// The same from running sums (zeros need not be stored): n values with sum and sum of squares.
inline MeanSe mean_se(double sum, double sum_sq, double n) {
    MeanSe m;
    m.mean = sum / n;
    m.se = std::sqrt(std::max(0.0, sum_sq / n - m.mean * m.mean) / (n - 1));
    return m;
}

} // namespace clppm::test
