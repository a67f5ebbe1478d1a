// Checks of a checkpoint's contents before a render continues from them. The checksum guards
// against damage, not against a crafted or foreign file: every field a render could not have
// produced (a negative or non-finite radius, counters that disagree, statistics that are not
// finite) is refused with a one-line error naming the checkpoint and the field, instead of
// hanging the render or changing its image.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/integrator_stats.h"
#include "io/checkpoint.h"
#include "shared_types.h"

namespace clppm {

// Throws Error "<path>: checkpoint field <what> is impossible" unless ok.
void require_checkpoint_field(const Checkpoint& ck, bool ok, const std::string& what);

// A header number that is finite and within [lo, hi].
double checkpoint_number(const Checkpoint& ck, const char* key, double lo, double hi);

// The largest radius a hit point starts from: R_0, or PPM's volume hit points' in media (the
// radii only shrink from theirs).
double largest_initial_radius(const IntegratorStats& stats);

// The photon integrators' counters after IntegratorBase::restore: every pass emitted
// photons_per_pass photons, R_0 lies in (0, the scene's diameter] and the mean radius in [0, the
// largest initial radius].
void check_photon_counters(const Checkpoint& ck, const IntegratorStats& stats, uint64_t photons_per_pass,
                           double scene_radius);

// Photon-mapping statistics: every R^2 finite in (0, r2_max] (the radius only shrinks from R_0),
// N, tau and the direct light finite and >= 0.
void check_hit_stats(const Checkpoint& ck, const std::vector<dev::HitStats>& stats, double r2_max);

// Sums of radiance (the path tracer's): finite and >= 0.
void check_radiance_sums(const Checkpoint& ck, const std::vector<double>& sums, const char* what);

} // namespace clppm
