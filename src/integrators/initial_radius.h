// The default initial gather radius R_0 of the photon-mapping integrators.
#pragma once
#include <vector>

namespace clppm {

// Twice the median pixel footprint of the hit points, kept within [1e-6, 0.05] of the scene's
// bounding diameter.
double initial_radius_heuristic(std::vector<float> footprints, double scene_radius);

// The volume hit points' initial radius (participating media), from their footprints: photons in
// a volume are sparser than on surfaces, so kVolumeRadiusScale times the surfaces' heuristic, kept
// within [1e-6, 0.1] of the diameter. 8 had the least box-4 error at 15 s on the fogged Cornell
// boxes (bench/RESULTS.md, "Photons in participating media"): 2 and 4 left more noise, 16 more blur.
constexpr double kVolumeRadiusScale = 8.0;
double initial_volume_radius(std::vector<float> footprints, double scene_radius);

// The beams' initial radius over the volume hit points' (kernels/beam.cl, --volume-gather beams):
// in the volumetric caustic at 128 x 128 and 15 s, 1 had the least box-4 error; 0.5 and 0.25 more
// (their gathers take more steps along each beam, fewer passes).
constexpr double kBeamRadiusScale = 1.0;

} // namespace clppm
