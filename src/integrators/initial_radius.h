// The default initial gather radius R_0 of the photon-mapping integrators.
#pragma once
#include <vector>

namespace clppm {

// Twice the median pixel footprint of the hit points, kept within [1e-6, 0.05] of the scene's
// bounding diameter.
double initial_radius_heuristic(std::vector<float> footprints, double scene_radius);

// The volume hit points' initial radius (participating media), from their footprints: photons in
// a volume are sparser than on surfaces, so kVolumeRadiusScale times the surfaces' heuristic, kept
// within [1e-6, 0.1] of the diameter.
constexpr double kVolumeRadiusScale = 4.0;
double initial_volume_radius(std::vector<float> footprints, double scene_radius);

} // namespace clppm
