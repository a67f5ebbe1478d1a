/* path_trace.cl: a unidirectional path tracer on the same scene kernels and the same BSDF
 * (kernels/bsdf.cl), for comparisons with photon mapping at equal time and to cross-check
 * diffuse scenes. At every vertex with non-delta lobes, one light sample (next-event
 * estimation) and the BSDF sample that continues the path both count emission, weighted by the
 * power heuristic (Veach 1997, Sec. 9.2); emission found after a delta lobe counts in full.
 * One sample per pixel per pass, accumulated in double; one launch may run several consecutive
 * passes (their samples added in pass order, so the sums are those of one launch a pass, bit for
 * bit, whatever the batch). Its numbers come from Owen-scrambled
 * Sobol' points over the passes (sobol.cl; `--sampler sobol`, the default) or from independent
 * random streams (`--sampler independent`); `--sampler zsobol` lays the pixels' points out on
 * the screen (sobol.cl, sobol_make_screen). */
#include "portability.h"
#include "rng.cl"
#include "sobol.cl"
#include "camera.cl"
#include "next_event.cl"
#include "pt_error.cl"
#include "mean_film.cl"
#include "dispersion.cl"
#include "medium.cl"
#include "medium_light.cl"

/* The path's numbers: a pixel's Sobol' points over the passes, or (built with
 * -DPATH_SAMPLER_INDEPENDENT) an independent stream. */
#ifdef PATH_SAMPLER_INDEPENDENT
#define PATH_QMC 0
typedef Rng PathSampler;
float path_1d(PathSampler* s) { return rng_float(s); }
float2 path_2d(PathSampler* s) {
    float u0 = rng_float(s);
    return (float2)(u0, rng_float(s));
}
#else
#define PATH_QMC 1
typedef Sobol PathSampler;
float path_1d(PathSampler* s) { return sobol_1d(s); }
float2 path_2d(PathSampler* s) { return sobol_2d(s); }
#endif

/* u_pick scaled into [0, share): the part of the light CDF below the world (world_by_bsdf). */
float share_pick(float u_pick, float share) {
    if (share == 1.0f) return u_pick;
    float v = u_pick * share;
    return v < share ? v : nextafter(share, 0.0f);
}

#define PATH_RR_DEPTH 5
#define PATH_RR_MAX_SURVIVAL 0.95f

/* One light sample from x for next-event estimation, with the path's numbers; a uniform world left
 * to the BSDF (world_by_bsdf) is not picked, the others' probabilities divided by pick_share. */
bool path_light_sample(SCENE_PARAMS, PathSampler* ps, float3 x, bool world_by_bsdf, float pick_share, LightSample* ls) {
    bool ok;
#if PATH_QMC
    /* The light and its point from one 2-D point (pick_light_reuse): 3.7% less error at equal
     * passes in the diffuse box, whose light is two triangles (bench/RESULTS.md). */
    float u_spare = path_1d(ps);
    ok = sample_light_reuse(SCENE_ARGS, x, pick_share, path_2d(ps), u_spare, ls);
#else
    if (world_by_bsdf) {
        float u_pick = rng_float(ps);
        float2 u_point = path_2d(ps);
        ok = sample_light_u(SCENE_ARGS, x, share_pick(u_pick, pick_share), u_point, ls);
    } else {
        ok = sample_light_full(SCENE_ARGS, x, ps, ls); /* a point only where it takes one */
    }
#endif
    if (world_by_bsdf && ok) {
        ls->contrib *= pick_share;
        ls->pdf_w /= pick_share;
    }
    return ok;
}

#if HAS_POINT_LIGHTS || HAS_SPOT_LIGHTS
/* Whether light l shines from a point: a point or a spot light. */
bool light_at_a_point(SCENE_PARAMS, uint l) {
    uint type = lights[l].type;
#if HAS_POINT_LIGHTS && HAS_SPOT_LIGHTS
    return type == LIGHT_POINT || type == LIGHT_SPOT;
#elif HAS_POINT_LIGHTS
    return type == LIGHT_POINT;
#else
    return type == LIGHT_SPOT;
#endif
}

/* The point and spot lights' share of the light a segment of the world's medium scatters, by
 * equiangular sampling towards a light picked as light samples pick (Kulla and Fajardo 2012): the
 * segment o + t d, t in [0, t_max), of a path of throughput beta (not included) at its start. Weighed
 * against the free flight's own light sample by the balance heuristic over the two distance densities:
 * near a light in thin fog, where free flights rarely stop, this finds the glow around it. */
float3 equiangular_next_event(SCENE_PARAMS, const Medium* m, float3 o, float3 d, float t_max, float3 beta, float share,
                              float2 u) {
    uint l = pick_light(SCENE_ARGS, share_pick(u.x, share));
    if (!light_at_a_point(SCENE_ARGS, l)) return (float3)(0.0f);
    float t, pdf_e;
    if (!equiangular_sample(o, d, t_max, load3g(lights[l].position), u.y, &t, &pdf_e)) return (float3)(0.0f);
    float3 x = o + d * t;
    LightSample ls;
    if (!sample_chosen_light(SCENE_ARGS, x, l, (float2)(0.0f), &ls)) return (float3)(0.0f);
    float ph = hg_phase(dot(d, ls.wi), m->g);
    if (!(ph > 0.0f) || trace_occluded(SCENE_ARGS, x, ls.wi, ls.dist)) return (float3)(0.0f);
    float p_d = medium_distance_pdf(m, beta, t);
    return m->albedo * m->sigma_t * medium_transmittance(m->sigma_t, t) * ls.contrib *
           medium_transmittance(m->sigma_t, ls.dist) * (share * ph / (pdf_e + p_d));
}
#endif

/* Light scattered at the medium point p towards -d (d: the direction the path arrived in) from the
 * light sample s: the phase function, the shadow ray and the medium's transmittance along it,
 * weighted by the power heuristic against sampling the phase function. */
float3 medium_next_event(SCENE_PARAMS, const Medium* m, float3 p, float3 d, bool ok, const LightSample* s) {
    if (!ok) return (float3)(0.0f);
    float3 wi, contrib;
    float dist, light_pdf;
    light_sample_out(s, &wi, &dist, &contrib, &light_pdf);
    float ph = hg_phase(dot(d, wi), m->g);
    if (!(ph > 0.0f) || trace_occluded(SCENE_ARGS, p, wi, dist)) return (float3)(0.0f);
    float mis = light_pdf > 0.0f ? power_heuristic(light_pdf, ph) : 1.0f;
    return contrib * light_sample_transmittance(SCENE_ARGS, m->sigma_t, s) * (ph * mis);
}

/* Pixel `pixel`'s sample of pass `pass` (counted from 1). */
float3 path_sample(SCENE_PARAMS, __constant Camera* cam, ulong seed, ulong pass, uint pixel, uint screen_log2) {
#if PATH_QMC
    /* passes count from 1: nets from index 0. screen_log2: L of sobol_make_screen's layout, or
     * SOBOL_PER_PIXEL for each pixel's own sequence */
    PathSampler ps = screen_log2 == SOBOL_PER_PIXEL
                         ? sobol_make(seed, pixel, pass - 1)
                         : sobol_make_screen(seed, pixel % cam->width, pixel / cam->width, pass - 1, screen_log2);
#else
    PathSampler ps = rng_make(seed, pass, pixel, RNG_PATH);
#endif
    float2 off = path_2d(&ps);
    off = (float2)(filter_warp(off.x), filter_warp(off.y));
    float2 lens = path_2d(&ps);
    float3 org, dir;
    camera_ray(cam, (float)(pixel % cam->width) + off.x, (float)(pixel / cam->width) + off.y, lens, &org, &dir);
    float3 L = (float3)(0.0f), beta = (float3)(1.0f);
    bool prev_delta = true; /* camera rays and delta lobes: emission found counts in full */
    bool chain = true;      /* every bounce so far delta: unlit surfaces are seen */
    float prev_pdf = 0.0f;
    const PassWavelength pw = pass_wavelength(seed, pass);
    /* A uniform world (the default white one, --env-color) is left to the BSDF's samples: one that
     * leaves the scene counts the world in full, and light samples go to the other lights alone,
     * picked in proportion to power among them (pbrt-v4's UniformInfiniteLight with
     * allowIncompletePDF). The world is the last light (src/scene/device_scene.cpp), so the others
     * hold the CDF below light_cdf[env_light]: pick_share, their part of the power (0: none, no
     * light sample). Uniform light samples, weighed against cosine-distributed BSDF samples,
     * lowered the error less than their shadow rays cost (bench/RESULTS.md, "A uniform world
     * found by the BSDF alone"). */
    const bool world_by_bsdf = HAS_ENV_LIGHT && info->env_light != ENV_UNIFORM &&
                               info->env_light + 1u == info->num_lights && lights[info->env_light].prim == ENV_UNIFORM;
    const float pick_share = world_by_bsdf ? light_cdf[info->env_light] : 1.0f;
    bool dispersed = false; /* the path has met a dispersive surface and carries W (dispersion.cl) */
    for (uint depth = 0; depth < info->max_bounces; ++depth) {
        Hit hit;
        const bool found = trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit);
        /* The medium the segment ran in (kernels/medium.cl): the world's, or a closed mesh's own
         * that scatters (inside); a mesh that only absorbs takes its toll at the surface below. */
        Medium med;
        bool inside = false;
        if (HAS_MEDIUM && segment_medium(SCENE_ARGS, found, dir, &hit, &med, &inside)) {
            /* A free flight, and a scattering there with a light sample and a direction from the
             * phase function, or the segment's transmittance. Inside a closed mesh no shadow ray
             * leaves (its surface stops them): unless the mesh holds a light, light arrives
             * through the surface's own vertices, and what a scattered ray finds counts in full. */
            const float3 d = normalize(dir);
            const float t_max = found ? hit.t * length(dir) : INFINITY;
            const float2 u_flight = path_2d(&ps);
            const bool light_samples =
                pick_share > 0.0f && (!inside || (materials[med.id - 1u].flags & MATERIAL_FLAG_HOLDS_LIGHTS) != 0u);
#if HAS_POINT_LIGHTS || HAS_SPOT_LIGHTS
            const float3 beta_seg = beta;
            const float2 u_eq = path_2d(&ps);
            if (light_samples)
                L += beta_seg * equiangular_next_event(SCENE_ARGS, &med, org, d, t_max, beta_seg, pick_share, u_eq);
#endif
            float t;
            if (medium_sample_distance(&med, t_max, u_flight, &beta, &t)) {
                beta *= med.albedo;
                float3 p = org + d * t;
                if (light_samples) {
                    LightSample ls;
                    bool ok = path_light_sample(SCENE_ARGS, &ps, p, world_by_bsdf, pick_share, &ls);
                    float3 ne = medium_next_event(SCENE_ARGS, &med, p, d, ok, &ls);
#if HAS_POINT_LIGHTS || HAS_SPOT_LIGHTS
                    /* a point or spot light: the balance heuristic against equiangular sampling */
                    if (ok && light_at_a_point(SCENE_ARGS, ls.light)) {
                        float p_d = medium_distance_pdf(&med, beta_seg, t);
                        ne *= p_d / (p_d + equiangular_pdf(org, d, t_max, load3g(lights[ls.light].position), t));
                    }
#endif
                    L += beta * ne;
                }
                float pdf;
                float3 wi = hg_sample(d, med.g, path_2d(&ps), &pdf);
                /* f / pdf = 1: the throughput changes only by the roulette */
                if (depth >= PATH_RR_DEPTH) {
                    float q = fmin(max3(beta), PATH_RR_MAX_SURVIVAL);
                    if (!(path_1d(&ps) < q)) break;
                    beta /= q;
                }
                prev_delta = inside && !light_samples; /* no light sample inside: what the ray finds counts in full */
                chain = false;
                prev_pdf = pdf;
                org = p;
                dir = wi;
                if (!(max3(beta) > 0.0f)) break;
                continue;
            }
            if (!(max3(beta) > 0.0f)) break;
        }
        if (!found) {
            if (HAS_ENV_LIGHT)
                L += beta *
                     escaped_radiance(SCENE_ARGS, normalize(dir), depth == 0, prev_delta || world_by_bsdf, prev_pdf);
            break;
        }
        Surface sf = make_surface(SCENE_ARGS, dir, &hit);
        if (HAS_VOLUME && !inside) beta *= volume_transmittance(SCENE_ARGS, &sf, sf.t * length(dir));
        float3 le = surface_emission(SCENE_ARGS, &sf, dir);
        if (max3(le) > 0.0f) {
            L += beta * le * (prev_delta ? 1.0f : emission_mis_share(SCENE_ARGS, &sf, dir, prev_pdf, pick_share));
        }
        if (HAS_UNLIT && chain) L += beta * surface_unlit(SCENE_ARGS, &sf);
        Bsdf b = surface_bsdf(SCENE_ARGS, &sf, TRANSPORT_RADIANCE);
        if (HAS_DISPERSION) disperse(SCENE_ARGS, &sf, &b, &pw, &dispersed, &beta);
        float3 wo = -dir;
        if (pick_share > 0.0f) {
            LightSample ls;
            bool ok = path_light_sample(SCENE_ARGS, &ps, sf.p, world_by_bsdf, pick_share, &ls);
            float3 ne = next_event_from(SCENE_ARGS, &b, sf.p, wo, LOBE_ALL, ok, &ls);
            if ((HAS_MEDIUM || HAS_VOLUME) && ok) ne *= surface_light_transmittance(SCENE_ARGS, &sf, &ls);
            L += beta * ne;
        }
        BsdfSample s;
        float u_lobe = path_1d(&ps);
        float2 u = path_2d(&ps);
        if (!bsdf_sample(&b, wo, LOBE_ALL, u_lobe, u.x, u.y, &s)) break;
        /* Russian roulette once the path has scattered PATH_RR_DEPTH times, survival by
         * throughput, at most PATH_RR_MAX_SURVIVAL (Mitsuba 3's path integrator: rr_depth 5,
         * 0.95). Started from the third vertex, as it was, it left 1.2 times the error at equal
         * time in diffuse rooms and 1.5 times under the sky (bench/RESULTS.md). */
        if (depth >= PATH_RR_DEPTH) {
            float q = fmin(max3(beta * s.weight), PATH_RR_MAX_SURVIVAL);
            if (!(path_1d(&ps) < q)) break;
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
    return L;
}

/* Passes first_pass .. first_pass + passes - 1 of the pixels below num_pixels. */
__kernel SCALAR_WORK_ITEMS void path_trace(SCENE_PARAMS, __constant Camera* cam, ulong seed, ulong first_pass,
                                           uint passes, uint num_pixels, uint screen_log2, __global double* accum) {
    uint pixel = get_global_id(0);
    if (pixel >= num_pixels) return;
    double3 sum = (double3)(accum[3 * pixel], accum[3 * pixel + 1], accum[3 * pixel + 2]);
    for (uint j = 0u; j < passes; ++j) {
        float3 L = path_sample(SCENE_ARGS, cam, seed, first_pass + j, pixel, screen_log2);
        sum.x += L.x;
        sum.y += L.y;
        sum.z += L.z;
    }
    accum[3 * pixel] = sum.x;
    accum[3 * pixel + 1] = sum.y;
    accum[3 * pixel + 2] = sum.z;
}
