/* radiance_estimate.cl: the radiance estimate of progressive photon mapping from a hit point's
 * statistics (Hachisuka et al. 2008, Eq. 11),
 *   L = tau / (pi R^2 N_emitted),
 * with tau in units of the total light power P (kernels/lights.cl), so the estimate is scaled by
 * P. The one formula of PPM's film (film.cl) and SPPM's (sppm.cl). Zero before any photon. */
#ifndef CLPPM_RADIANCE_ESTIMATE_CL
#define CLPPM_RADIANCE_ESTIMATE_CL

#include "shared_types.h"

double3 photon_radiance(__global const HitStats* s, double total_power, double photons_emitted) {
    if (!(photons_emitted > 0.0 && s->r2 > 0.0)) return (double3)(0.0);
    return (double3)(s->tau[0], s->tau[1], s->tau[2]) * (total_power / (M_PI * s->r2 * photons_emitted));
}

#endif
