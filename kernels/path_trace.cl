/* path_trace.cl: a unidirectional path tracer on the same scene kernels and the same BSDF
 * (kernels/bsdf.cl), for comparisons with photon mapping at equal time and to cross-check
 * diffuse scenes. At every vertex with non-delta lobes, one light sample (next-event
 * estimation) and the BSDF sample that continues the path both count emission, weighted by the
 * power heuristic (Veach 1997, Sec. 9.2); emission found after a delta lobe counts in full.
 * One sample per pixel per pass, accumulated in double. */
#include "rng.cl"
#include "camera.cl"
#include "next_event.cl"
#include "pt_error.cl"
#include "mean_film.cl"
#include "dispersion.cl"

__kernel void path_trace(SCENE_PARAMS, __constant Camera* cam, ulong seed, ulong pass, uint num_pixels,
                         __global double* accum) {
    uint pixel = get_global_id(0);
    if (pixel >= num_pixels) return;
    Rng rng = rng_make(seed, pass, pixel, RNG_PATH);
    float2 off = pixel_sample_offset(0, 1, true, &rng);
    float2 lens = (float2)(rng_float(&rng), rng_float(&rng));
    float3 org, dir;
    camera_ray(cam, (float)(pixel % cam->width) + off.x, (float)(pixel / cam->width) + off.y, lens, &org, &dir);
    float3 L = (float3)(0.0f), beta = (float3)(1.0f);
    bool prev_delta = true; /* camera rays and delta lobes: emission found counts in full */
    bool chain = true;      /* every bounce so far delta: unlit surfaces are seen */
    float prev_pdf = 0.0f;
    const PassWavelength pw = pass_wavelength(seed, pass);
    bool dispersed = false; /* the path has met a dispersive surface and carries W (dispersion.cl) */
    for (uint depth = 0; depth < info->max_bounces; ++depth) {
        Hit hit;
        if (!trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit)) {
            if (HAS_ENV_LIGHT)
                L += beta * escaped_radiance(SCENE_ARGS, normalize(dir), depth == 0, prev_delta, prev_pdf);
            break;
        }
        Surface sf = make_surface(SCENE_ARGS, dir, &hit);
        if (HAS_VOLUME) beta *= volume_transmittance(SCENE_ARGS, &sf, sf.t * length(dir));
        float3 le = surface_emission(SCENE_ARGS, &sf, dir);
        if (max3(le) > 0.0f) {
            L += beta * le * (prev_delta ? 1.0f : emission_mis(SCENE_ARGS, &sf, dir, prev_pdf));
        }
        if (HAS_UNLIT && chain) L += beta * surface_unlit(SCENE_ARGS, &sf);
        Bsdf b = surface_bsdf(SCENE_ARGS, &sf);
        if (HAS_DISPERSION) disperse(SCENE_ARGS, &sf, &b, &pw, &dispersed, &beta);
        float3 wo = -dir;
        L += beta * next_event(SCENE_ARGS, &b, sf.p, wo, LOBE_ALL, &rng);
        BsdfSample s;
        float u0 = rng_float(&rng), u1 = rng_float(&rng), u2 = rng_float(&rng);
        if (!bsdf_sample(&b, wo, LOBE_ALL, u0, u1, u2, &s)) break;
        /* Russian roulette after the first bounces, survival by throughput. */
        if (depth >= 2) {
            float q = fmin(max3(beta * s.weight), 1.0f);
            if (!(rng_float(&rng) < q)) break;
            beta *= s.weight / q;
        } else {
            beta *= s.weight;
        }
        prev_delta = s.delta;
        chain = chain && s.delta;
        prev_pdf = s.pdf;
        dir = s.wi;
        org = offset_origin(SCENE_ARGS, sf.p, s.below ? -sf.ng : sf.ng);
        if (!(max3(beta) > 0.0f)) break;
    }
    if (!all(isfinite(L))) L = (float3)(0.0f); /* never let one bad sample poison a pixel */
    accum[3 * pixel] += L.x;
    accum[3 * pixel + 1] += L.y;
    accum[3 * pixel + 2] += L.z;
}
