/* next_event.cl: next-event estimation with multiple importance sampling, shared by the path
 * tracer and the eye pass (which uses it on the smooth lobes it samples through, so highlights of
 * small and punctual lights survive there). One light sample, shadow-tested, weighted by the
 * power heuristic (Veach 1997, Sec. 9.2) against the BSDF's sampling of the same direction over
 * the same lobes; emission that a BSDF-sampled ray finds takes the complementary weight
 * (emission_mis). */
#ifndef CLPPM_NEXT_EVENT_CL
#define CLPPM_NEXT_EVENT_CL

#include "lights.cl"
#include "bsdf.cl"

float power_heuristic(float a, float b) {
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/* Light reflected towards wo by the lobes in mask, from the light sample s (ok: it contributes). */
float3 next_event_from(SCENE_PARAMS, const Bsdf* b, float3 p, float3 wo, uint mask, bool ok, const LightSample* s) {
    float3 wi, contrib;
    float dist, light_pdf;
    if (!ok) return (float3)(0.0f);
    light_sample_out(s, &wi, &dist, &contrib, &light_pdf);
    float cos_x = dot(wi, b->ns);
    /* A light below the surface is seen only through rough glass. */
    bool through = cos_x < 0.0f;
    if (!bsdf_connects(b, wi, mask)) return (float3)(0.0f);
    float3 f = bsdf_eval(b, wo, wi, mask);
    if (!(max3(f) > 0.0f)) return (float3)(0.0f);
    if (trace_occluded(SCENE_ARGS, offset_origin(SCENE_ARGS, p, through ? -b->ng : b->ng), wi, dist))
        return (float3)(0.0f);
    float mis = light_pdf > 0.0f ? power_heuristic(light_pdf, bsdf_pdf(b, wo, wi, mask)) : 1.0f;
    return f * contrib * bsdf_segment_transmittance(b, wi, dist) * (fabs(cos_x) * mis);
}

/* One light sample from a random stream. */
float3 next_event(SCENE_PARAMS, const Bsdf* b, float3 p, float3 wo, uint mask, Rng* rng) {
    LightSample s;
    bool ok = sample_light_full(SCENE_ARGS, p, rng, &s);
    return next_event_from(SCENE_ARGS, b, p, wo, mask, ok, &s);
}

/* One light sample from the uniforms u_pick (the light) and u (its point). */
float3 next_event_u(SCENE_PARAMS, const Bsdf* b, float3 p, float3 wo, uint mask, float u_pick, float2 u) {
    LightSample s;
    bool ok = sample_light_u(SCENE_ARGS, p, u_pick, u, &s);
    return next_event_from(SCENE_ARGS, b, p, wo, mask, ok, &s);
}

/* The MIS weight of emission found at surface sf by a ray along dir that was sampled with
 * solid-angle density bsdf_pdf (not a delta lobe, not a camera ray), where light samples pick
 * lights with their probabilities divided by pick_share (kernels/path_trace.cl: a uniform world
 * left to the BSDF's samples; 1 elsewhere). */
float emission_mis_share(SCENE_PARAMS, const Surface* sf, float3 dir, float bsdf_pdf, float pick_share) {
    float light_pdf = area_light_pdf(SCENE_ARGS, emitter_power_per_area(SCENE_ARGS, sf->prim, sf->material),
                                     sf->t * sf->t * dot(dir, dir), fabs(dot(dir, sf->ng)) / length(dir));
    /* pick_share 0: no light samples are drawn, and the BSDF's sample takes the whole weight. */
    return pick_share > 0.0f ? power_heuristic(bsdf_pdf, light_pdf / pick_share) : 1.0f;
}

float emission_mis(SCENE_PARAMS, const Surface* sf, float3 dir, float bsdf_pdf) {
    return emission_mis_share(SCENE_ARGS, sf, dir, bsdf_pdf, 1.0f);
}

/* What a ray along unit dir that leaves the scene sees: the environment, weighted by MIS
 * against light sampling unless it came from a camera or a delta lobe (bsdf_pdf 0), nothing
 * for a camera ray when the environment is hidden. */
float3 escaped_radiance(SCENE_PARAMS, float3 dir, bool camera_ray, bool delta, float bsdf_pdf) {
    if (!HAS_ENV_LIGHT || info->env_light == ENV_UNIFORM) return (float3)(0.0f);
    __global const Light* L = &lights[info->env_light];
    if (camera_ray && L->position[2] != 0.0f) return (float3)(0.0f);
    float3 le = env_radiance(L, textures, texels, dir);
    if (delta) return le;
    return le * power_heuristic(bsdf_pdf, env_light_pdf(SCENE_ARGS, dir));
}

#endif
