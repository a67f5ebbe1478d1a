#include "integrators/initial_radius.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace clppm {

double initial_radius_heuristic(std::vector<float> footprints, double scene_radius) {
    double diameter = 2 * scene_radius;
    if (footprints.empty()) return 1e-3 * diameter;
    auto mid = footprints.begin() + footprints.size() / 2;
    std::nth_element(footprints.begin(), mid, footprints.end());
    double r = 2.0 * double(*mid);
    if (!std::isfinite(r)) r = 1e-3 * diameter;
    return std::clamp(r, 1e-6 * diameter, 0.05 * diameter);
}

double initial_volume_radius(std::vector<float> footprints, double scene_radius) {
    const double diameter = 2 * scene_radius;
    const double r = kVolumeRadiusScale * initial_radius_heuristic(std::move(footprints), scene_radius);
    return std::clamp(r, 1e-6 * diameter, 0.1 * diameter);
}

InitialRadii initial_radii(const std::vector<dev::HitPoint>& hitpoints, double radius, double scene_radius,
                           bool media) {
    std::vector<float> footprints, volume_footprints;
    for (const dev::HitPoint& hp : hitpoints) {
        if (hp.pixel == HITPOINT_NONE) continue;
        (hp.alpha < 0 ? volume_footprints : footprints).push_back(std::fabs(hp.footprint));
    }
    InitialRadii r;
    if (media)
        r.volume = initial_volume_radius(volume_footprints.empty() ? footprints : volume_footprints, scene_radius);
    r.surface = radius > 0 ? radius : initial_radius_heuristic(std::move(footprints), scene_radius);
    return r;
}

} // namespace clppm
