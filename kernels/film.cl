/* film.cl: the pixel radiance from the hit points' statistics,
 *   L = tau / (pi R^2 N_emitted)   (Hachisuka et al. 2008, Eq. 11: radiance_estimate.cl;
 *                                   a volume hit point's over its sphere's volume)
 * plus emission seen along the eye paths and the running mean of explicit direct lighting,
 * averaged over the pixel's samples (box filter). */
#include "radiance_estimate.cl"

__kernel void ppm_film(__global const HitPoint* hitpoints, __global const HitStats* stats,
                       __global const uint* pixel_first, __global const float4* emitted, uint num_pixels, uint spp,
                       double total_power, double photons_emitted, double passes, __global float4* image) {
    uint p = get_global_id(0);
    if (p >= num_pixels) return;
    double3 L = (double3)(emitted[p].x, emitted[p].y, emitted[p].z);
    for (uint k = pixel_first[p]; k < pixel_first[p + 1]; ++k) {
        __global const HitStats* s = &stats[k];
        L += hitpoint_photon_radiance(&hitpoints[k], s, total_power, photons_emitted);
        if (passes > 0.0) L += (double3)(s->direct[0], s->direct[1], s->direct[2]) / passes;
    }
    L /= (double)spp;
    image[p] = (float4)((float)L.x, (float)L.y, (float)L.z, 1.0f);
}
