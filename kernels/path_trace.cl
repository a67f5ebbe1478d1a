/* path_trace.cl: a unidirectional path tracer on the same scene kernels, for comparisons with
 * photon mapping at equal time and to cross-check diffuse scenes. Next-event estimation at
 * diffuse vertices; emission found by a ray after a diffuse bounce is then skipped (the light
 * was already counted by NEE), after a specular event it is counted. One sample per pixel per
 * pass, accumulated in double. */
#include "rng.cl"
#include "camera.cl"
#include "lights.cl"
#include "bsdf.cl"

/* Next-event estimation at a non-specular surface (nonspecular_brdf: Lambertian when alpha is
 * 0, else GGX): one light sample, shadow-tested. */
float3 path_nee(SCENE_PARAMS, const Surface* sf, float3 wo, float3 color, float alpha, Rng* rng) {
    float3 wi, contrib;
    float dist;
    if (!sample_light(SCENE_ARGS, sf->p, rng, &wi, &dist, &contrib)) return (float3)(0.0f);
    float cos_x = dot(wi, sf->ns);
    if (cos_x <= 0.0f || dot(wi, sf->ng) <= 0.0f) return (float3)(0.0f);
    if (trace_occluded(SCENE_ARGS, offset_origin(SCENE_ARGS, sf->p, sf->ng), wi, dist)) return (float3)(0.0f);
    return nonspecular_brdf(sf->ns, wo, wi, color, alpha) * contrib * cos_x;
}

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
    bool count_emission = true;
    for (uint depth = 0; depth < info->max_bounces; ++depth) {
        Hit hit;
        if (!trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit)) break;
        Surface sf = make_surface(SCENE_ARGS, dir, &hit);
        if (count_emission) L += beta * surface_emission(SCENE_ARGS, &sf);
        float3 base = surface_base_color(SCENE_ARGS, &sf);
        uint kind = resolve_kind(SCENE_ARGS, &sf, rng_float(&rng));
        if (kind == MATERIAL_DIFFUSE) {
            L += beta * path_nee(SCENE_ARGS, &sf, -dir, base, 0.0f, &rng);
            count_emission = false;
            /* Russian roulette after the first bounces, survival by throughput. */
            float q = fmin(max3(beta * base), 1.0f);
            if (depth >= 2) {
                if (!(rng_float(&rng) < q)) break;
                beta *= base / q;
            } else {
                beta *= base;
            }
            dir = sample_cosine_hemisphere(sf.ns, rng_float(&rng), rng_float(&rng));
            if (dot(dir, sf.ng) <= 0.0f) break;
            org = offset_origin(SCENE_ARGS, sf.p, sf.ng);
        } else if (HAS_GLOSSY && kind == MATERIAL_GLOSSY) {
            /* Rough glossy surfaces take next-event estimation like diffuse ones; smooth ones are
             * treated like mirrors (emission found by the sampled ray counts). */
            float alpha = material_alpha(&materials[sf.material]);
            bool rough = alpha >= GLOSSY_HITPOINT_ALPHA;
            if (rough) L += beta * path_nee(SCENE_ARGS, &sf, -dir, base, alpha, &rng);
            count_emission = !rough;
            float3 wi;
            float3 w = ggx_sample(sf.ns, -dir, base, alpha, rng_float(&rng), rng_float(&rng), &wi);
            if (dot(wi, sf.ng) <= 0.0f) break;
            if (depth >= 2) {
                float q = fmin(max3(beta * w), 1.0f);
                if (!(rng_float(&rng) < q)) break;
                beta *= w / q;
            } else {
                beta *= w;
            }
            dir = wi;
            org = offset_origin(SCENE_ARGS, sf.p, sf.ng);
        } else if (HAS_MIRROR && kind == MATERIAL_MIRROR) {
            beta *= base;
            dir = specular_reflect(&sf, dir);
            org = offset_origin(SCENE_ARGS, sf.p, sf.ng);
            count_emission = true;
        } else if (HAS_DIELECTRIC) {
            if (!sample_dielectric(SCENE_ARGS, &sf, rng_float(&rng), base, &dir, &org, &beta)) break;
            count_emission = true;
        }
        if (!(max3(beta) > 0.0f)) break;
    }
    if (!all(isfinite(L))) L = (float3)(0.0f); /* never let one bad sample poison a pixel */
    accum[3 * pixel] += L.x;
    accum[3 * pixel + 1] += L.y;
    accum[3 * pixel + 2] += L.z;
}

__kernel void pt_film(__global const double* accum, uint num_pixels, double passes, __global float4* image) {
    uint p = get_global_id(0);
    if (p >= num_pixels) return;
    double s = passes > 0.0 ? 1.0 / passes : 0.0;
    image[p] = (float4)((float)(accum[3 * p] * s), (float)(accum[3 * p + 1] * s), (float)(accum[3 * p + 2] * s), 1.0f);
}
