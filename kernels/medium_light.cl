/* medium_light.cl: light samples through the world's medium (kernels/medium.cl), one rule for the
 * path tracer, the eye pass and the hit points' direct light: the shadow ray of a light sample
 * takes the transmittance of the medium it runs in, to the light, or to infinity for the lights
 * that lie there. */
#ifndef CLPPM_MEDIUM_LIGHT_CL
#define CLPPM_MEDIUM_LIGHT_CL

#include "lights.cl"
#include "medium.cl"

/* How far a light sample's light is through the world's medium: a directional light and the
 * environment lie at infinity, where an unbounded medium lets nothing through (as rays that leave the
 * scene find); the others at the sample's distance. */
float medium_light_distance(SCENE_PARAMS, const LightSample* s) {
    uint type = lights[s->light].type;
    if (HAS_DIRECTIONAL_LIGHTS && type == LIGHT_DIRECTIONAL) return INFINITY;
    if (HAS_ENV_LIGHT && type == LIGHT_ENVIRONMENT) return INFINITY;
    return s->dist;
}

/* The transmittance along the light sample s (drawn: ok) through a medium of extinction sigma. */
float3 light_sample_transmittance(SCENE_PARAMS, float3 sigma, const LightSample* s) {
    return medium_transmittance(sigma, medium_light_distance(SCENE_ARGS, s));
}

/* The transmittance along the light sample s that leaves the surface sf, through the volume it
 * leaves into (leaving_volume): the world's medium, or the mesh the surface lies in; 1 where that
 * is clear, and into the surface's own mesh, whose absorption bsdf_segment_transmittance takes. */
float3 surface_light_transmittance(SCENE_PARAMS, const Surface* sf, const LightSample* s) {
    const uint v = leaving_volume(SCENE_ARGS, sf, s->wi);
    if (v == sf->material + 1u) return (float3)(1.0f);
    const float3 sigma = volume_sigma_t(SCENE_ARGS, v);
    if (!(max3(sigma) > 0.0f)) return (float3)(1.0f);
    return light_sample_transmittance(SCENE_ARGS, sigma, s);
}

/* Photons from a light at infinity (directional, environment) cross the world's medium from
 * infinity: its transmittance to infinity, 0 in every channel with extinction, as light samples
 * take it. 1 for the other lights and in a clear world. */
float3 emitted_through_world_medium(SCENE_PARAMS, bool finite) {
    if (finite || !world_has_medium(info)) return (float3)(1.0f);
    return medium_transmittance(world_sigma_t(info), INFINITY);
}

#endif
