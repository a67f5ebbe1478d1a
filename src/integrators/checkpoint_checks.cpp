#include "integrators/checkpoint_checks.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace clppm {

namespace {

bool finite_nonnegative(double v) { return std::isfinite(v) && v >= 0; }

} // namespace

void require_checkpoint_field(const Checkpoint& ck, bool ok, const std::string& what) {
    if (!ok) throw Error(ck.path + ": checkpoint field " + what + " is impossible (a crafted or foreign file?)");
}

double checkpoint_number(const Checkpoint& ck, const char* key, double lo, double hi) {
    const Json& h = ck.header;
    require_checkpoint_field(ck, h.contains(key) && h[key].is_number(), std::string(key) + " (missing)");
    const double v = h[key].get<double>();
    require_checkpoint_field(ck, std::isfinite(v) && v >= lo && v <= hi, std::string(key) + " = " + h[key].dump());
    return v;
}

void check_photon_counters(const Checkpoint& ck, const IntegratorStats& stats, uint64_t photons_per_pass,
                           double scene_radius) {
    const bool counted = photons_per_pass > 0 && stats.passes <= UINT64_MAX / photons_per_pass &&
                         stats.photons_emitted == stats.passes * photons_per_pass;
    require_checkpoint_field(ck, counted,
                             "photons_emitted = " + std::to_string(stats.photons_emitted) + " after " +
                                 std::to_string(stats.passes) + " passes of " + std::to_string(photons_per_pass));
    const double r0 = stats.initial_radius;
    require_checkpoint_field(ck, std::isfinite(r0) && r0 > 0 && r0 <= 2 * scene_radius, "initial_radius");
    const double r_max = largest_initial_radius(stats);
    require_checkpoint_field(
        ck, std::isfinite(stats.mean_radius) && stats.mean_radius >= 0 && stats.mean_radius <= r_max * (1 + 1e-9),
        "mean_radius");
}

double largest_initial_radius(const IntegratorStats& stats) {
    return std::max(stats.initial_radius, stats.initial_volume_radius);
}

void check_hit_stats(const Checkpoint& ck, const std::vector<dev::HitStats>& stats, double r2_max) {
    for (size_t i = 0; i < stats.size(); ++i) {
        const dev::HitStats& s = stats[i];
        bool ok = std::isfinite(s.r2) && s.r2 > 0 && s.r2 <= r2_max && finite_nonnegative(s.n);
        for (int c = 0; c < 3; ++c) ok = ok && finite_nonnegative(s.tau[c]) && finite_nonnegative(s.direct[c]);
        require_checkpoint_field(ck, ok, "stats[" + std::to_string(i) + "]");
    }
}

void check_radiance_sums(const Checkpoint& ck, const std::vector<double>& sums, const char* what) {
    for (size_t i = 0; i < sums.size(); ++i)
        require_checkpoint_field(ck, finite_nonnegative(sums[i]), std::string(what) + "[" + std::to_string(i) + "]");
}

} // namespace clppm
