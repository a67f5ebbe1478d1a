/* sppm.cl: what stochastic PPM (Hachisuka and Jensen 2009) and probabilistic PPM (Knaus and
 * Zwicker 2011) add to the PPM kernels. Both trace a new eye sample per pixel every pass.
 *   SPPM keeps PPM's statistics (R, N, tau) per pixel and applies the same update to whatever
 *        visible point the pixel has this pass; seen emission and direct light are averaged.
 *   PPPM makes each pass an independent photon-map estimate with one radius r_i for all pixels,
 *        r_{i+1}^2 = r_i^2 (i + alpha)/(i + 1) (Knaus and Zwicker, Eq. 20), and averages the pass
 *        images: HitStats.tau holds the running sum of f Phi / (pi r_i^2). */
#include "radiance_estimate.cl"
#include "hitpoint.cl"

__kernel void accumulate_emission(__global const float4* sample_emission, __global HitStats* stats, uint n) {
    uint i = get_global_id(0);
    if (i >= n) return;
    float4 e = sample_emission[i];
    stats[i].direct[0] += e.x;
    stats[i].direct[1] += e.y;
    stats[i].direct[2] += e.z;
}

/* One PPPM pass: the standard density estimate with this pass's radius, added to the sum. */
__kernel void pppm_accumulate(__global const PassFlux* pass, __global const HitPoint* hitpoints,
                              __global HitStats* stats, uint n, double inv_area) {
    uint i = get_global_id(0);
    if (i >= n || pass[i].m == 0) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (hitpoint_in_volume(hp)) return; /* volume_accumulate */
    for (int c = 0; c < 3; ++c)
        stats[i].tau[c] += (double)hp->weight[c] * ((double)pass[i].flux[c] / FLUX_FIXED_SCALE) * inv_area;
}

/* A pass's volume hit points (shared_types.h): their estimate from this pass's photons with the
 * pass's radius r_v, the same for every pixel and shrinking over the passes as probabilistic PPM's
 * does in three dimensions (Knaus and Zwicker 2011, Sec. 4.3: r_{i+1}^3 = r_i^3 (i + alpha) /
 * (i + 1)), joins the running sum of the pixel's direct light, which SPPM's and PPPM's films
 * average over the passes: scale = P / (M 4/3 pi r_v^3), the photons' flux in units of P. So a
 * pixel may see a surface in one pass and fog in the next; its surface statistics are untouched
 * by the passes where it saw fog (ppm_update). */
__kernel void volume_accumulate(__global const PassFlux* pass, __global const HitPoint* hitpoints,
                                __global HitStats* stats, uint n, double scale) {
    uint i = get_global_id(0);
    if (i >= n || pass[i].m == 0) return;
    __global const HitPoint* hp = &hitpoints[i];
    if (!hitpoint_in_volume(hp)) return;
    for (int c = 0; c < 3; ++c)
        stats[i].direct[c] += (double)hp->weight[c] * ((double)pass[i].flux[c] / FLUX_FIXED_SCALE) * scale;
}

/* SPPM: L = tau / (pi R^2 N_emitted) + (emission + direct) / passes, one visible point per pixel. */
__kernel void sppm_film(__global const HitStats* stats, uint num_pixels, double total_power, double photons_emitted,
                        double passes, __global float4* image) {
    uint p = get_global_id(0);
    if (p >= num_pixels) return;
    __global const HitStats* s = &stats[p];
    double3 L = photon_radiance(s, total_power, photons_emitted);
    if (passes > 0.0) L += (double3)(s->direct[0], s->direct[1], s->direct[2]) / passes;
    image[p] = (float4)((float)L.x, (float)L.y, (float)L.z, 1.0f);
}

/* PPPM: the mean of the pass images; each pass's photon term is P / M * sum f Phi / (pi r_i^2). */
__kernel void pppm_film(__global const HitStats* stats, uint num_pixels, double power_per_photon, double passes,
                        __global float4* image) {
    uint p = get_global_id(0);
    if (p >= num_pixels) return;
    __global const HitStats* s = &stats[p];
    double3 L = (double3)(0.0);
    if (passes > 0.0)
        L = ((double3)(s->tau[0], s->tau[1], s->tau[2]) * power_per_photon +
             (double3)(s->direct[0], s->direct[1], s->direct[2])) /
            passes;
    image[p] = (float4)((float)L.x, (float)L.y, (float)L.z, 1.0f);
}
