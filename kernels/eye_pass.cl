/* eye_pass.cl: the first pass of progressive photon mapping (Hachisuka et al. 2008, Sec. 4.1).
 * Each pixel sample follows specular chains from the camera and stores a hit point wherever a
 * surface has lobes the gather can estimate (diffuse, and reflection at least
 * GLOSSY_HITPOINT_ALPHA rough: bsdf_gathered_lobes in kernels/bsdf.cl); smoother lobes and glass,
 * rough or smooth, are sampled through. Where a surface splits the path (a hit point and a smooth reflection,
 * glass's reflection and refraction), the branches are followed with their weights while slots
 * remain (EYE_SLOTS per sample), so the stored
 * set of hit points carries no sampling noise from those choices; beyond that one branch is
 * chosen at random with the same expected value. Emission met on the way is added to the
 * sample's radiance; on the smooth lobes it samples through (not mirrors), the eye path also
 * samples the lights (kernels/next_event.cl), and emission its rays find there is weighted by
 * MIS against that, so no hit point is needed for their direct light.
 * In a participating medium (kernels/medium.cl) each segment takes a free flight first; where it
 * collides, the path ends in a volume hit point there (hitpoint.cl store_volume_hitpoint). SPPM and
 * PPPM (`beams`) make the first scattering segment of each sample a beam instead (kernels/beam.cl)
 * as far as it runs within the sphere around the scene and the camera (beam_span), and go on
 * through it with its transmittance: the beam gathers the fog along the whole of it.
 * Stochastic PPM and PPPM build this with EYE_SLOTS 1 and run it every pass with a new `pass`:
 * one visible point per pixel, every choice sampled, new jitter and lens position each pass. */
#include "portability.h"
#include "rng.cl"
#include "camera.cl"
#include "bsdf.cl"
#include "next_event.cl"
#include "hitpoint.cl"
#include "dispersion.cl"
#include "medium_light.cl"

#ifndef EYE_SLOTS
#define EYE_SLOTS PPM_EYE_SLOTS /* the host passes -DEYE_SLOTS=PPM_EYE_SLOTS or SPPM_EYE_SLOTS */
#endif
/* One visible point per pixel in media: eye_pass takes `beams` (whether the hit point buffer holds
 * a beam slot per sample after the hit points) and may store one there. */
#define EYE_BEAMS (HAS_MEDIUM && EYE_SLOTS == 1)
#if EYE_BEAMS
#define EYE_BEAMS_PARAM , uint beams
#else
#define EYE_BEAMS_PARAM
#endif
/* A split is only worth a slot when both branches carry real weight. */
#define SPLIT_MIN_WEIGHT 0.02f

typedef struct {
    float3 org, dir, weight;
    float path_length;
    uint depth;
    float pdf;      /* density the direction was sampled with (MIS against light sampling) */
    bool delta;     /* a camera ray or a delta lobe: emission found counts in full */
    bool chain;     /* every bounce from the camera delta: unlit surfaces are seen */
    bool dispersed; /* the path has met a dispersive surface and carries W (dispersion.cl) */
} EyeRay;

/* One way an eye path can go on from a surface: a new ray, or a hit point here. */
typedef struct {
    float3 weight;
    float3 dir; /* ray branches */
    bool below; /* the ray leaves through the surface (refraction) */
    bool hitpoint;
    float magnitude; /* what the branch is expected to carry: chooses between branches */
    float pdf;       /* ray branches: as EyeRay */
    bool delta;
} Branch;

Branch no_branch(void) {
    Branch b;
    b.weight = (float3)(0.0f);
    b.dir = (float3)(0.0f);
    b.below = false;
    b.hitpoint = false;
    b.magnitude = 0.0f;
    b.pdf = 0.0f;
    b.delta = true;
    return b;
}

Branch ray_branch(float3 weight, float3 dir, bool below) {
    Branch b = no_branch();
    b.weight = weight;
    b.dir = dir;
    b.below = below;
    b.magnitude = max3(weight);
    return b;
}

#define MAX_BRANCHES 4

/* The lobes the eye path samples through with one ray (and lights by next-event estimation):
 * the reflection lobes hit points do not keep, and rough glass; smooth glass branches apart. */
uint eye_followed_lobes(const Bsdf* bsdf) {
    uint followed = LOBE_ALL & ~bsdf_gathered(bsdf);
    return glass_is_rough(bsdf) ? followed : followed & ~LOBE_GLASS;
}

/* The continuations of an eye path at a surface (kernels/bsdf.cl decides which lobes are whose):
 * a hit point for the lobes it keeps; one sampled ray for the other reflection lobes; and, at
 * glass, its reflection and its refraction with their Fresnel weights (radiance: the refraction
 * compressed by 1/eta^2, refraction_scale in kernels/bsdf.cl). Returns how many. */
uint surface_branches(const Bsdf* bsdf, float3 wo, float3 weight, Rng* rng, Branch* br) {
    uint n = 0;
    if (bsdf_plain_lambert(bsdf)) { /* one way on: a hit point */
        if (!(bsdf->dielectric > 0.0f)) return 0;
        Branch b = no_branch();
        b.weight = weight;
        b.hitpoint = true;
        b.magnitude = max3(weight);
        br[0] = b;
        return 1;
    }
    float cos_o = dot(bsdf->ns, wo);
    uint gathered = bsdf_gathered(bsdf);
    float kept = lobe_weights(bsdf, wo, gathered).total;
    if (kept > 0.0f) {
        Branch b = no_branch();
        b.weight = weight;
        b.hitpoint = true;
        b.magnitude = max3(weight) * kept;
        br[n++] = b;
    }
    if (!HAS_NON_DIFFUSE) return n;
    uint followed = eye_followed_lobes(bsdf);
    if (lobe_weights(bsdf, wo, followed).total > 0.0f) {
        BsdfSample s;
        float u0 = rng_float(rng), u1 = rng_float(rng), u2 = rng_float(rng);
        if (bsdf_sample(bsdf, wo, followed, u0, u1, u2, &s)) {
            br[n] = ray_branch(weight * s.weight, s.wi, s.below);
            br[n].pdf = s.pdf;
            br[n++].delta = s.delta;
        }
    }
    if (HAS_GLASS && bsdf->glass > 0.0f && !glass_is_rough(bsdf)) {
        float F = fresnel_dielectric(cos_o, bsdf->eta);
        float3 r = bsdf_mirror(bsdf, wo);
        br[n++] = ray_branch(weight * (bsdf->glass * F * layers_scale(bsdf, wo, r)), r, false);
        if (F < 1.0f) {
            float3 t = bsdf->thin ? -wo : refract_dir(-wo, bsdf->ns, bsdf->eta);
            if (dot(t, bsdf->ng) < 0.0f)
                br[n++] =
                    ray_branch(weight * bsdf->base *
                                   (bsdf->glass * (1.0f - F) * layers_scale(bsdf, wo, t) * refraction_scale(bsdf)),
                               t, true);
        }
    }
    return n;
}

/* A free flight over [t0, t1) of a segment in the medium m: true with the collision's distance in
 * *t, and *weight as medium_sample_distance leaves it. */
bool eye_collides(const Medium* m, float t0, float t1, Rng* rng, float3* weight, float* t) {
    const float u0 = rng_float(rng), u1 = rng_float(rng);
    float s;
    if (!medium_sample_distance(m, t1 - t0, (float2)(u0, u1), weight, &s)) return false;
    *t = t0 + s;
    return true;
}

#if EYE_BEAMS
/* The span [*ta, *tb] of the segment o + t d, t in [0, t_seg), a beam covers: its part within the
 * sphere that holds the scene and the camera, where the photons are dense (beyond it, free flights
 * sample the rest of an unbounded medium). False where that part is empty. */
bool beam_span(__constant SceneInfo* info, __constant Camera* cam, float3 o, float3 d, float t_seg, float* ta,
               float* tb) {
    const float3 c = load3c(info->center);
    const float R = fmax(info->radius, length(load3c(cam->origin) - c) + cam->lens_radius) * 1.001f;
    const float3 oc = o - c;
    const float b = dot(oc, d), disc = b * b - (dot(oc, oc) - R * R);
    if (!(disc > 0.0f)) return false;
    const float q = sqrt(disc);
    *ta = fmax(-b - q, 0.0f);
    *tb = fmin(-b + q, t_seg);
    return *tb > *ta;
}
#endif

__kernel SCALAR_WORK_ITEMS void eye_pass(SCENE_PARAMS, __constant Camera* cam, ulong seed, ulong pass,
                                         uint first_sample, uint num_samples, uint spp, __global HitPoint* hitpoints,
                                         __global float4* sample_emission EYE_BEAMS_PARAM) {
    uint i = get_global_id(0);
    if (i >= num_samples) return;
    uint gsample = first_sample + i;
    uint pixel = gsample / spp, s = gsample % spp;
    Rng rng = rng_make(seed, pass, gsample, RNG_EYE);

    float2 off = pixel_sample_offset(s, spp, EYE_SLOTS == 1, &rng);
    float2 lens = (float2)(rng_float(&rng), rng_float(&rng));
    float px = (float)(pixel % cam->width) + off.x, py = (float)(pixel / cam->width) + off.y;

    EyeRay stack[EYE_SLOTS];
    uint top = 0, stored = 0;
    camera_ray(cam, px, py, lens, &stack[0].org, &stack[0].dir);
    stack[0].weight = (float3)(1.0f);
    stack[0].path_length = 0.0f;
    stack[0].depth = 0;
    stack[0].pdf = 0.0f;
    stack[0].delta = true;
    stack[0].chain = true;
    stack[0].dispersed = false;
    /* SPPM and PPPM: the pass's wavelength, which its photons share. PPM keeps its hit points for
     * the whole render: each pixel's samples take wavelengths of their own, stratified over them
     * (docs/scenes.md, "dispersion", says what that means for PPM). */
    const PassWavelength pw =
        EYE_SLOTS == 1 ? pass_wavelength(seed, pass) : pass_wavelength(splitmix64(seed ^ splitmix64(pixel)), s);
    top = 1;
    float3 emitted = (float3)(0.0f);
    __global HitPoint* out = &hitpoints[(size_t)i * EYE_SLOTS];
    for (uint k = 0; k < EYE_SLOTS; ++k) out[k].pixel = HITPOINT_NONE;
#if EYE_BEAMS
    bool beam_free = beams != 0;
    if (beam_free) hitpoints[num_samples + i].pixel = HITPOINT_NONE;
#endif

    while (top > 0) {
        EyeRay r = stack[--top];
        Hit hit;
        const bool found = trace_closest(SCENE_ARGS, r.org, r.dir, INFINITY, &hit);
        bool inside = false;
        Medium med;
        if (HAS_MEDIUM && segment_medium(SCENE_ARGS, found, r.dir, &hit, &med, &inside)) {
            /* A free flight in the medium: a collision makes a volume hit point there (its slot is
             * this ray's), which gathers the photons stored in media; otherwise the segment's
             * transmittance over its probability, on to the surface. A beam's span [ta, tb] takes
             * no free flight: its transmittance is exact. */
            const float3 d = normalize(r.dir);
            const float t_seg = found ? hit.t * length(r.dir) : INFINITY;
            float ta = t_seg, t;
#if EYE_BEAMS
            float tb = t_seg;
            if (!(beam_free && max3(med.albedo) > 0.0f && beam_span(info, cam, r.org, d, t_seg, &ta, &tb)))
                ta = tb = t_seg;
#endif
            bool collided = eye_collides(&med, 0.0f, ta, &rng, &r.weight, &t);
#if EYE_BEAMS
            if (!collided && tb > ta) {
                store_beam(&hitpoints[num_samples + i], pixel, r.org + d * ta, d, tb - ta, r.weight, med.sigma_t,
                           med.albedo, med.g, med.id,
                           with_dispersed(camera_footprint(cam, r.path_length + 0.5f * (ta + tb)), r.dispersed));
                beam_free = false;
                r.weight *= medium_transmittance(med.sigma_t, tb - ta);
                collided = eye_collides(&med, tb, t_seg, &rng, &r.weight, &t);
            }
#endif
            if (collided) {
                store_volume_hitpoint(&out[stored++], pixel, r.org + d * t, -d, r.weight * med.albedo, med.sigma_t,
                                      med.g, med.id,
                                      with_dispersed(camera_footprint(cam, r.path_length + t), r.dispersed));
                continue;
            }
            if (!(max3(r.weight) > 0.0f)) continue;
        }
        if (!found) {
            if (HAS_ENV_LIGHT)
                emitted += r.weight * escaped_radiance(SCENE_ARGS, normalize(r.dir), r.depth == 0, r.delta, r.pdf);
            continue;
        }
        Surface sf = make_surface(SCENE_ARGS, r.dir, &hit);
        if (HAS_VOLUME && !inside) r.weight *= volume_transmittance(SCENE_ARGS, &sf, sf.t * length(r.dir));
        float3 le = surface_emission(SCENE_ARGS, &sf, r.dir);
        if (max3(le) > 0.0f) emitted += r.weight * le * (r.delta ? 1.0f : emission_mis(SCENE_ARGS, &sf, r.dir, r.pdf));
        if (HAS_UNLIT && r.chain) emitted += r.weight * surface_unlit(SCENE_ARGS, &sf);
        if (r.depth + 1 >= info->max_bounces) continue;
        float plen = r.path_length + sf.t;

        Bsdf bsdf = surface_bsdf(SCENE_ARGS, &sf, TRANSPORT_RADIANCE);
        if (HAS_DISPERSION) disperse(SCENE_ARGS, &sf, &bsdf, &pw, &r.dispersed, &r.weight);
        /* The lobes the eye path samples through see the lights directly too (with MIS): no hit
         * point gathers their direct light, and a sampled ray never finds a punctual light. */
        if (!bsdf_plain_lambert(&bsdf) && (!bsdf_is_mirror(&bsdf) || (has_coat(&bsdf) && !coat_is_mirror(&bsdf)))) {
            uint followed = eye_followed_lobes(&bsdf);
            if (lobe_weights(&bsdf, -r.dir, followed).total > 0.0f) {
                LightSample ls;
                const bool ok = sample_light_full(SCENE_ARGS, sf.p, &rng, &ls);
                float3 ne = next_event_from(SCENE_ARGS, &bsdf, sf.p, -r.dir, followed, ok, &ls);
                if ((HAS_MEDIUM || HAS_VOLUME) && ok) ne *= surface_light_transmittance(SCENE_ARGS, &sf, &ls);
                emitted += r.weight * ne;
            }
        }
        Branch br[MAX_BRANCHES];
        uint nb = surface_branches(&bsdf, -r.dir, r.weight, &rng, br);
        bool take[MAX_BRANCHES];
        uint count = 0;
        float total = 0.0f, least = INFINITY;
        for (uint k = 0; k < nb; ++k) {
            take[k] = br[k].magnitude > 0.0f;
            if (!take[k]) continue;
            ++count;
            total += br[k].magnitude;
            least = fmin(least, br[k].magnitude);
        }
        if (count > 1) {
            /* Split only when slots are free for every branch and all matter; otherwise keep
             * one, chosen in proportion to magnitude and reweighted (expected value unchanged). */
            bool room = top + stored + count <= EYE_SLOTS;
            if (!room || least < SPLIT_MIN_WEIGHT * max3(r.weight)) {
                float u = rng_float(&rng) * total, acc = 0.0f;
                uint pick = nb;
                for (uint k = 0; k < nb; ++k) {
                    if (!take[k]) continue;
                    pick = k;
                    if (u < acc + br[k].magnitude) break;
                    acc += br[k].magnitude;
                }
                for (uint k = 0; k < nb; ++k) take[k] = k == pick;
                br[pick].weight *= total / br[pick].magnitude;
            }
        }
        for (uint k = 0; k < nb; ++k) {
            if (!take[k]) continue;
            Branch b = br[k];
            if (b.hitpoint) {
                store_hitpoint(&out[stored++], pixel, sf.p, -r.dir, b.weight, &bsdf,
                               with_dispersed(camera_footprint(cam, plen), r.dispersed),
                               HAS_MEDIUM ? surface_arrival_volume(SCENE_ARGS, &sf) : 0u,
                               HAS_MEDIUM ? leaving_volume(SCENE_ARGS, &sf, r.dir) : 0u);
            } else {
                EyeRay nr = {offset_origin(SCENE_ARGS, sf.p, b.below ? -sf.ng : sf.ng),
                             b.dir,
                             b.weight,
                             plen,
                             r.depth + 1,
                             b.pdf,
                             b.delta,
                             r.chain && b.delta,
                             r.dispersed};
                stack[top++] = nr;
            }
        }
    }
    sample_emission[i] = (float4)(emitted, 0.0f);
}
