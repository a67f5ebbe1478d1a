/* photon_trace.cl: one refinement pass's photons (Hachisuka et al. 2008, Sec. 4.2). Each work
 * item emits one photon in proportion to light power, scatters it by sampling the surface's BSDF
 * (kernels/bsdf.cl) with Russian roulette, and stores every hit on a surface with lobes that get
 * hit points (bsdf_gathered_lobes).
 * With skip_direct set (explicit direct lighting at hit points), the first diffuse hit of a
 * photon that came straight from the light is not stored: that light is sampled directly. */
#ifndef CLPPM_PHOTON_TRACE_CL
#define CLPPM_PHOTON_TRACE_CL

#include "portability.h"
#include "rng.cl"
#include "lights.cl"
#include "bsdf.cl"
#include "dispersion.cl"
#include "hash_grid.cl"
#include "medium_light.cl"

/* A stored photon: hit point p with normal n, flux, direction wi back along the path. */
Photon make_photon(float3 p, float3 n, float3 flux, float3 wi, bool dispersed) {
    Photon ph;
    ph.pos[0] = p.x;
    ph.pos[1] = p.y;
    ph.pos[2] = p.z;
    ph.normal_oct = oct_encode(n);
    ph.flux[0] = with_dispersed(flux.x, dispersed);
    ph.flux[1] = flux.y;
    ph.flux[2] = flux.z;
    ph.wi_oct = oct_encode(wi);
    return ph;
}

/* A photon stored at a collision in medium `medium` (Medium.id, in normal_oct; PHOTON_VOLUME_FLAG):
 * flux times sigma_t T / pdf. */
Photon make_volume_photon(float3 p, float3 flux, float3 wi, bool dispersed, uint medium) {
    Photon ph = make_photon(p, wi, flux, wi, dispersed);
    ph.flux[1] = as_float(as_uint(ph.flux[1]) | PHOTON_VOLUME_FLAG);
    ph.normal_oct = medium;
    return ph;
}

void put_photon(__global Photon* photons, uint capacity, volatile __global uint* counter, const Photon* ph) {
    uint slot = atomic_inc(counter);
    if (slot >= capacity) return; /* the host sees counter > capacity, grows the buffer, re-runs */
    photons[slot] = *ph;
}

/* Where a Markov chain of photon paths (kernels/photon_chain.cl) keeps a photon: where some hit
 * point may gather it, by the cells their spheres marked this pass. Elsewhere a photon adds
 * nothing to any pixel, so that its path is invisible (V = 0) exactly when it stores none. */
#ifdef PHOTON_VISUAL_IMPORTANCE
#define PHOTON_SEEN(p) (seen[grid_bucket(seen_grid, grid_cell(seen_grid, p))] != 0)
/* The chain also records every photon the path would store, seen or not, up to
 * PHOTON_CHAIN_CACHE of them (*n_rec counts them all), to deposit its state again without tracing
 * it (photon_chain.cl). */
#define SEEN_PARAMS , __constant GridInfo *seen_grid, __global const uchar *seen, Photon *rec, uint *n_rec
#define SEEN_ARGS , seen_grid, seen, rec, n_rec
#define RECORD_PHOTON(ph)                                                                                              \
    do {                                                                                                               \
        if (*n_rec < PHOTON_CHAIN_CACHE) rec[*n_rec] = (ph);                                                           \
        ++*n_rec;                                                                                                      \
    } while (0)
#else
#define PHOTON_SEEN(p) true
#define SEEN_PARAMS
#define SEEN_ARGS
#define RECORD_PHOTON(ph)
#endif

/* Roulette of photons scattered in media (photon_path), as Mitsuba 3's volpath caps its survival. */
#define PHOTON_MEDIUM_RR_DEPTH 5
#define PHOTON_MEDIUM_RR_SURVIVAL 0.95f

/* Keeps the photon ph found at p (recorded for the chains; stored where seen): 1 if stored. */
uint keep_photon(const Photon* ph, float3 p, __global Photon* photons, uint capacity,
                 volatile __global uint* counter SEEN_PARAMS) {
    RECORD_PHOTON(*ph);
    if (!PHOTON_SEEN(p)) return 0;
    put_photon(photons, capacity, counter, ph);
    return 1;
}

/* Traces one photon path from rng's numbers and returns how many of its hits it stored. In a
 * medium (kernels/medium.cl) a free flight may end in a collision, where the photon is stored
 * (volume hit points gather it) and scatters by the phase function with the albedo as its
 * survival probability; a collision, like a surface, is one bounce. */
uint photon_path(SCENE_PARAMS, Rng* rng, const PassWavelength* pw, uint skip_direct, __global Photon* photons,
                 uint capacity, volatile __global uint* counter SEEN_PARAMS) {
    LightEmission e;
    emit_light(SCENE_ARGS, rng, &e);
    float3 org = e.org, dir = e.dir, flux = e.flux;
    if (HAS_MEDIUM) flux *= emitted_through_world_medium(SCENE_ARGS, e.finite);
    if (!(max3(flux) > 0.0f)) return 0;
    bool dispersed = false; /* the photon has met a dispersive surface and carries W (dispersion.cl) */
    uint stored = 0;

    for (uint bounce = 0; bounce < info->max_bounces; ++bounce) {
        Hit hit;
        const bool found = trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit);
        bool inside = false;
        Medium med;
        if (HAS_MEDIUM && segment_medium(SCENE_ARGS, found, dir, &hit, &med, &inside)) {
            const float3 d = normalize(dir);
            const float u0 = rng_float(rng), u1 = rng_float(rng);
            float t;
            if (medium_sample_distance(&med, found ? hit.t * length(dir) : INFINITY, (float2)(u0, u1), &flux, &t)) {
                const float3 p = org + d * t;
                if (!(skip_direct && bounce == 0)) {
                    const Photon ph = make_volume_photon(p, flux, -d, dispersed, med.id);
                    stored += keep_photon(&ph, p, photons, capacity, counter SEEN_ARGS);
                }
                /* after PHOTON_MEDIUM_RR_DEPTH events at most PHOTON_MEDIUM_RR_SURVIVAL survive: in an
                 * unbounded white medium a photon that leaves the scene would wander forever */
                const float q =
                    fmin(max3(med.albedo), bounce >= PHOTON_MEDIUM_RR_DEPTH ? PHOTON_MEDIUM_RR_SURVIVAL : 1.0f);
                if (q < 1.0f && !(rng_float(rng) < q)) return stored;
                flux *= med.albedo / q;
                const float u2 = rng_float(rng), u3 = rng_float(rng);
                float pdf;
                dir = hg_sample(d, med.g, (float2)(u2, u3), &pdf);
                org = p;
                if (!(max3(flux) > 0.0f)) return stored;
                continue;
            }
            if (!(max3(flux) > 0.0f)) return stored;
        }
        if (!found) return stored;
        Surface sf = make_surface(SCENE_ARGS, dir, &hit);
        if (HAS_VOLUME && !inside) {
            flux *= volume_transmittance(SCENE_ARGS, &sf, sf.t * length(dir));
            if (!(max3(flux) > 0.0f)) return stored;
        }
        Bsdf bsdf = surface_bsdf(SCENE_ARGS, &sf, TRANSPORT_IMPORTANCE);
        if (HAS_DISPERSION) disperse(SCENE_ARGS, &sf, &bsdf, pw, &dispersed, &flux);
        float3 wo = -dir;
        /* Stored where the eye pass puts hit points: on surfaces with lobes the gather keeps. */
        if (!(skip_direct && bounce == 0) && bsdf_has_gathered(&bsdf)) {
            const Photon ph = make_photon(sf.p, sf.ns, flux, wo, dispersed);
            stored += keep_photon(&ph, sf.p, photons, capacity, counter SEEN_ARGS);
        }
        /* The BSDF is reciprocal, so sampling it from the photon's side scatters flux correctly. */
        BsdfSample s;
        float u0 = rng_float(rng), u1 = rng_float(rng), u2 = rng_float(rng);
        if (!bsdf_sample(&bsdf, wo, LOBE_ALL, u0, u1, u2, &s)) return stored;
        /* Russian roulette with the scattering weight as survival probability keeps flux near
         * constant. */
        float q = fmin(max3(s.weight), 1.0f);
        if (q < 1.0f && !(rng_float(rng) < q)) return stored;
        flux *= s.weight / q;
        dir = s.wi;
        org = offset_origin(SCENE_ARGS, sf.p, s.below ? -sf.ng : sf.ng);
        if (!(max3(flux) > 0.0f)) return stored;
    }
    return stored;
}

#ifdef PHOTON_VISUAL_IMPORTANCE
#define SEEN_KERNEL_PARAMS , __constant GridInfo *seen_grid, __global const uchar *seen
#else
#define SEEN_KERNEL_PARAMS
#endif

__kernel SCALAR_WORK_ITEMS void photon_trace(SCENE_PARAMS, ulong seed, ulong pass, uint first_photon, uint num_photons,
                                             uint skip_direct, __global Photon* photons, uint capacity,
                                             volatile __global uint* counter SEEN_KERNEL_PARAMS) {
    uint i = get_global_id(0);
    if (i >= num_photons || info->num_lights == 0) return;
    Rng rng = rng_make(seed, pass, first_photon + i, RNG_PHOTON);
    const PassWavelength pw = pass_wavelength(seed, pass);
#ifdef PHOTON_VISUAL_IMPORTANCE
    Photon rec[PHOTON_CHAIN_CACHE];
    uint recorded = 0, *n_rec = &recorded;
#endif
    photon_path(SCENE_ARGS, &rng, &pw, skip_direct, photons, capacity, counter SEEN_ARGS);
}

#endif
