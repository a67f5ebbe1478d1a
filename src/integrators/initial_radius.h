// The default initial gather radius R_0 of the photon-mapping integrators.
#pragma once
#include <vector>

#include "shared_types.h"

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

// The first eye pass's hit points' initial radii (HITPOINT_NONE slots skipped): the surfaces'
// (`radius` where > 0, else the heuristic over their footprints) and, where the scene has media,
// the volume hit points' and beams' (initial_volume_radius over theirs, or over the surfaces' where
// none was made; 0 without media). PPM's and SPPM's prepare share it.
struct InitialRadii {
    double surface = 0, volume = 0;
};
InitialRadii initial_radii(const std::vector<dev::HitPoint>& hitpoints, double radius, double scene_radius, bool media);

// The beams' initial radius over the volume hit points' (kernels/beam.cl, --volume-gather beams):
// in the volumetric caustic at 128 x 128 and 15 s, 1 had the least box-4 error; 0.5 and 0.25 more
// (their gathers take more steps along each beam, fewer passes).
constexpr double kBeamRadiusScale = 1.0;

} // namespace clppm
