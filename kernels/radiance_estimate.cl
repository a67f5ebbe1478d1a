/* radiance_estimate.cl: the radiance estimate of progressive photon mapping from a hit point's
 * statistics (Hachisuka et al. 2008, Eq. 11),
 *   L = tau / (pi R^2 N_emitted),
 * with tau in units of the total light power P (kernels/lights.cl), so the estimate is scaled by
 * P. The one formula of PPM's film (film.cl) and SPPM's (sppm.cl). Zero before any photon.
 * PPM's fixed volume hit points divide by the sphere's volume instead (ppm_update.cl),
 *   L = tau / (4/3 pi R^3 N_emitted),
 * tau summing p Phi_p / sigma_t times the hit point's weight (gather_query.cl VolumeQuery). */
#ifndef CLPPM_RADIANCE_ESTIMATE_CL
#define CLPPM_RADIANCE_ESTIMATE_CL

#include "shared_types.h"
#include "hitpoint.cl"

double3 photon_radiance(__global const HitStats* s, double total_power, double photons_emitted) {
    if (!(photons_emitted > 0.0 && s->r2 > 0.0)) return (double3)(0.0);
    return (double3)(s->tau[0], s->tau[1], s->tau[2]) * (total_power / (M_PI * s->r2 * photons_emitted));
}

/* A fixed hit point's estimate (PPM): a surface's, or a volume hit point's in its sphere. */
double3 hitpoint_photon_radiance(__global const HitPoint* hp, __global const HitStats* s, double total_power,
                                 double photons_emitted) {
    if (!hitpoint_in_volume(hp)) return photon_radiance(s, total_power, photons_emitted);
    if (!(photons_emitted > 0.0 && s->r2 > 0.0)) return (double3)(0.0);
    const double volume = 4.0 / 3.0 * M_PI * s->r2 * sqrt(s->r2);
    return (double3)(s->tau[0], s->tau[1], s->tau[2]) * (total_power / (volume * photons_emitted));
}

#endif
