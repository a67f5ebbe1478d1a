#include "integrators/work_balance.h"

#include <algorithm>
#include <cmath>

#include "device/cluster.h"

namespace clppm {

void WorkBalance::record(double units, double seconds) {
    if (!(units > 0) || !(seconds > 0) || !std::isfinite(seconds)) return;
    samples_.emplace_back(units, seconds);
    if (samples_.size() > kWindow) samples_.pop_front();
}

std::pair<double, double> WorkBalance::model() const {
    if (samples_.empty()) return {0.0, 0.0};
    double su = 0, st = 0;
    for (const auto& [u, t] : samples_) su += u, st += t;
    const double n = double(samples_.size()), mu = su / n, mt = st / n;
    double suu = 0, sut = 0;
    for (const auto& [u, t] : samples_) suu += (u - mu) * (u - mu), sut += (u - mu) * (t - mt);
    // The shares must differ by a few percent for the slope to mean anything.
    if (samples_.size() >= 3 && suu > n * (0.05 * mu) * (0.05 * mu)) {
        const double b = sut / suu, a = mt - b * mu;
        if (b > 0 && a >= 0) return {a, b};
        if (b > 0) return {0.0, mt / mu}; // a negative fixed part: noise; per unit only
    }
    return {0.0, mt / mu};
}

std::vector<uint32_t> WorkBalance::split(uint32_t total, const std::vector<double>& a, const std::vector<double>& b) {
    const size_t n = b.size();
    std::vector<uint32_t> c(n, 0);
    if (n == 0) return c;
    // Every process keeps a floor of a tenth of an equal share, so that none is starved and each
    // goes on measuring itself (a process given nothing would never be measured again).
    const uint32_t floor_share = uint32_t(total / (10 * n));
    const double rest = double(total) - double(floor_share) * double(n);
    bool known = a.size() == n;
    for (size_t r = 0; r < n && known; ++r) known = b[r] > 0 && std::isfinite(b[r]) && a[r] >= 0 && std::isfinite(a[r]);
    std::vector<double> share(n, rest / double(n));
    if (known) {
        // With the floor given, process r's time is a'_r + b_r x_r, a'_r = a_r + b_r floor.
        // T = (rest + sum a'_r / b_r) / sum 1 / b_r over the processes that get more; one whose
        // fixed part alone exceeds T gets only the floor, and T is solved again without it.
        std::vector<bool> in(n, true);
        for (bool changed = true; changed;) {
            changed = false;
            double num = rest, den = 0;
            for (size_t r = 0; r < n; ++r)
                if (in[r]) num += (a[r] + b[r] * floor_share) / b[r], den += 1 / b[r];
            const double T = num / den;
            for (size_t r = 0; r < n; ++r) {
                share[r] = in[r] ? (T - a[r]) / b[r] - floor_share : 0.0;
                if (in[r] && share[r] < 0) in[r] = false, changed = true;
            }
        }
    }
    uint32_t given = 0;
    for (size_t r = 1; r < n; ++r) {
        c[r] = floor_share + uint32_t(std::clamp(std::round(share[r]), 0.0, rest));
        c[r] = std::min(c[r], total - given);
        given += c[r];
    }
    c[0] = total - given; // the first takes the rounding
    return c;
}

std::vector<uint32_t> ranks_split(uint32_t total, const WorkBalance& mine) {
    const auto [a, b] = mine.model();
    const std::vector<double> all = cluster().all_values(std::vector<double>{a, b});
    std::vector<double> as, bs;
    for (size_t r = 0; r + 1 < all.size(); r += 2) as.push_back(all[r]), bs.push_back(all[r + 1]);
    return WorkBalance::split(total, as, bs);
}

} // namespace clppm
