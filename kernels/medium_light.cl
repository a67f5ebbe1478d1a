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

/* The world's medium's transmittance along the light sample s that leaves the surface sf: 1 where
 * the world is clear or the shadow ray runs inside a mesh (kernels/medium.cl). */
float3 surface_light_transmittance(SCENE_PARAMS, const Surface* sf, const LightSample* s) {
    if (!world_has_medium(info) || !leaving_in_world_medium(SCENE_ARGS, sf, s->wi)) return (float3)(1.0f);
    return light_sample_transmittance(SCENE_ARGS, world_sigma_t(info), s);
}

/* Photons from a light at infinity (directional, environment) cross the world's medium from
 * infinity: its transmittance to infinity, 0 in every channel with extinction, as light samples
 * take it. 1 for the other lights and in a clear world. */
float3 emitted_through_world_medium(SCENE_PARAMS, bool finite) {
    if (finite || !world_has_medium(info)) return (float3)(1.0f);
    return medium_transmittance(world_sigma_t(info), INFINITY);
}

#endif
