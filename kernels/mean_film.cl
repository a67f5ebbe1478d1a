/* mean_film.cl: the image of an integrator whose passes each add one unbiased sample's radiance
 * per pixel to a running sum in double (the path tracer, vertex connection and merging): the sum
 * over the passes divided by their number. */
#ifndef CLPPM_MEAN_FILM_CL
#define CLPPM_MEAN_FILM_CL

__kernel void mean_film(__global const double* accum, uint num_pixels, double passes, __global float4* image) {
    uint p = get_global_id(0);
    if (p >= num_pixels) return;
    double s = passes > 0.0 ? 1.0 / passes : 0.0;
    image[p] = (float4)((float)(accum[3 * p] * s), (float)(accum[3 * p + 1] * s), (float)(accum[3 * p + 2] * s), 1.0f);
}

#endif
