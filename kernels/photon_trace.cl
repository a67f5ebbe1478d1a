/* photon_trace.cl: one refinement pass's photons (Hachisuka et al. 2008, Sec. 4.2). Each work
 * item emits one photon in proportion to light power, follows it through specular events and
 * diffuse and glossy bounces with Russian roulette, and stores every hit on a surface that gets
 * hit points (diffuse, and glossy at least GLOSSY_HITPOINT_ALPHA rough).
 * With skip_direct set (explicit direct lighting at hit points), the first diffuse hit of a
 * photon that came straight from the light is not stored: that light is sampled directly. */
#include "rng.cl"
#include "lights.cl"
#include "bsdf.cl"

void store_photon(__global Photon* photons, uint capacity, volatile __global uint* counter, float3 p, float3 n,
                  float3 flux, float3 wi) {
    uint slot = atomic_inc(counter);
    if (slot >= capacity) return; /* the host sees counter > capacity, grows the buffer, re-runs */
    __global Photon* ph = &photons[slot];
    ph->pos[0] = p.x; ph->pos[1] = p.y; ph->pos[2] = p.z;
    ph->normal_oct = oct_encode(n);
    ph->flux[0] = flux.x; ph->flux[1] = flux.y; ph->flux[2] = flux.z;
    ph->wi_oct = oct_encode(wi);
}

__kernel void photon_trace(SCENE_PARAMS, ulong seed, ulong pass, uint first_photon, uint num_photons,
                           uint skip_direct, __global Photon* photons, uint capacity,
                           volatile __global uint* counter) {
    uint i = get_global_id(0);
    if (i >= num_photons || info->num_lights == 0) return;
    Rng rng = rng_make(seed, pass, first_photon + i, RNG_PHOTON);
    float3 org, dir, flux;
    emit_photon(SCENE_ARGS, &rng, &org, &dir, &flux);
    if (!(max3(flux) > 0.0f)) return;

    for (uint bounce = 0; bounce < info->max_bounces; ++bounce) {
        Hit hit;
        if (!trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit)) return;
        Surface sf = make_surface(SCENE_ARGS, dir, &hit);
        float3 base = surface_base_color(SCENE_ARGS, &sf);
        uint kind = resolve_kind(SCENE_ARGS, &sf, rng_float(&rng));
        if (kind == MATERIAL_DIFFUSE) {
            if (!(skip_direct && bounce == 0))
                store_photon(photons, capacity, counter, sf.p, sf.ns, flux, -dir);
            /* Russian roulette with the albedo as survival probability keeps flux near constant. */
            float q = fmin(max3(base), 1.0f);
            if (!(rng_float(&rng) < q)) return;
            flux *= base / q;
            dir = sample_cosine_hemisphere(sf.ns, rng_float(&rng), rng_float(&rng));
            if (dot(dir, sf.ng) <= 0.0f) return;
            org = offset_origin(SCENE_ARGS, sf.p, sf.ng);
        } else if (HAS_GLOSSY && kind == MATERIAL_GLOSSY) {
            float alpha = material_alpha(&materials[sf.material]);
            /* Stored where the eye pass puts hit points (rough enough), as on diffuse surfaces. */
            if (alpha >= GLOSSY_HITPOINT_ALPHA && !(skip_direct && bounce == 0))
                store_photon(photons, capacity, counter, sf.p, sf.ns, flux, -dir);
            float3 wo;
            float3 w = ggx_sample(sf.ns, -dir, base, alpha, rng_float(&rng), rng_float(&rng), &wo);
            if (dot(wo, sf.ng) <= 0.0f) return;
            float q = fmin(max3(w), 1.0f);
            if (!(rng_float(&rng) < q)) return;
            flux *= w / q;
            dir = wo;
            org = offset_origin(SCENE_ARGS, sf.p, sf.ng);
        } else if (HAS_MIRROR && kind == MATERIAL_MIRROR) {
            flux *= base;
            dir = specular_reflect(&sf, dir);
            org = offset_origin(SCENE_ARGS, sf.p, sf.ng);
        } else if (HAS_DIELECTRIC) {
            if (!sample_dielectric(SCENE_ARGS, &sf, rng_float(&rng), base, &dir, &org, &flux)) return;
        }
        if (!(max3(flux) > 0.0f)) return;
    }
}
