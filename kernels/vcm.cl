/* vcm.cl: vertex connection and merging (Georgiev, Krivanek, Davidovic, Slusallek 2012), and
 * bidirectional path tracing as its connections-only case, on the scene kernels and the one
 * scattering interface (kernels/bsdf.cl) the other integrators use. The formulation is SmallVCM's
 * (vertexcm.hxx), with the MIS weights in kernels/vcm_mis.h. A pass:
 *  1. vcm_light: N_L light sub-paths (one per pixel), each stored vertex by vertex (LightVertex,
 *     linked to its predecessor) and connected to the camera (light tracing, t = 1) into a
 *     fixed-point image, so that the sum does not depend on the order threads add in;
 *  2. the hashed grid over the stored vertices (kernels/hash_grid.cl with GRID_ELEM LightVertex);
 *  3. vcm_camera: one camera sub-path per pixel, which counts emission it finds (s = 0), samples
 *     the lights (s = 1), connects to the vertices of the light sub-path of the same index
 *     (s, t >= 2), and merges with every light vertex within the radius (merging); it alone writes
 *     its pixel.
 * When the light vertices of a pass do not fit the device at once, the light sub-paths are traced
 * in batches and every batch runs step 3 again: the camera sub-paths are the same (their random
 * numbers depend on (seed, pass, pixel) only), their own techniques count in the first batch and
 * the connections in the batch that holds their light sub-path.
 *
 * Units: light sub-paths carry flux in units of SceneInfo.total_power (as photons do) and every
 * distance in the MIS weights is taken relative to the scene (area_scale = R^2 of the bounding
 * sphere), so the weights and the fixed-point sums do not depend on light power or scene scale;
 * the host scales the light side back by total_power / R^2 (light_unit). */
#include "portability.h"
#include "rng.cl"
#include "camera.cl"
#include "lights.cl"
#include "bsdf.cl"
#include "next_event.cl"
#include "vcm_mis.h"
#include "gather_common.cl"
#include "fixed_point.cl"
#include "dispersion.cl"

#define RNG_VCM_LIGHT_SAMPLE                                                                                           \
    7u /* the camera sub-path's light samples: a stream of their own, so that
                                 * batches that skip them trace the same camera sub-path */

bool vcm_uses_connections(uint mode) { return mode == VCM_MODE_VCM || mode == VCM_MODE_BPT; }
bool vcm_uses_merging(uint mode) { return mode == VCM_MODE_VCM || mode == VCM_MODE_VM; }

/* Whether a segment from x (leaving on the side of unit w, with geometric normal nx) to y (reached
 * on the side of -w, normal ny) is free: both ends offset off their surfaces. */
bool vcm_visible(SCENE_PARAMS, float3 x, float3 nx, float3 y, float3 ny, float3 w) {
    float3 a = offset_origin(SCENE_ARGS, x, dot(w, nx) > 0.0f ? nx : -nx);
    float3 b = offset_origin(SCENE_ARGS, y, dot(w, ny) < 0.0f ? ny : -ny);
    float3 d = b - a;
    float len = length(d);
    if (!(len > 0.0f)) return false;
    return !trace_occluded(SCENE_ARGS, a, d / len, len);
}

/* ---- light sub-paths -------------------------------------------------------------------------- */

/* t = 1: the light vertex at sf (BSDF b, light arriving from wo, throughput T, MIS state m) seen by
 * the camera through one lens point (rng: a thin lens), added to the fixed-point splat image
 * (SmallVCM ConnectToCamera). The lens point's density and the lens area in the importance cancel. */
void vcm_connect_to_camera(SCENE_PARAMS, __constant Camera* cam, const Surface* sf, const Bsdf* b, float3 wo, float3 T,
                           const VcmMis* m, float light_paths, float vm_factor, float area_scale, uint mode,
                           volatile __global long* splat, float splat_scale, Rng* rng) {
    uint pixel;
    float cos_theta;
    float3 c;
    float2 lens = (float2)(0.5f, 0.5f);
    if (HAS_THIN_LENS && cam->lens_radius > 0.0f) lens = (float2)(rng_float(rng), rng_float(rng));
    if (!camera_project(cam, sf->p, lens, &pixel, &cos_theta, &c)) return;
    float3 d = c - sf->p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return;
    float3 w = d / sqrt(dist2);
    if (!bsdf_connects(b, w, LOBE_ALL)) return;
    float3 f = bsdf_eval(b, wo, w, LOBE_ALL);
    if (!(max3(f) > 0.0f)) return;
    /* The pixel's density for this vertex, per unit (scene-relative) area. */
    float camera_pdf_a = camera_pixel_pdf_w(cam, cos_theta) * fabs(dot(b->ns, w)) / (dist2 / area_scale);
    float weight = 1.0f;
    if (mode != VCM_MODE_LT)
        weight =
            vcm_weight_camera_connection(m, camera_pdf_a, light_paths, bsdf_pdf_rev(b, wo, w, LOBE_ALL), vm_factor);
    float3 v = T * f * bsdf_segment_transmittance(b, w, sqrt(dist2)) * (weight * camera_pdf_a / light_paths);
    if (!all(isfinite(v)) || !(max3(v) > 0.0f)) return;
    float3 a = offset_origin(SCENE_ARGS, sf->p, dot(w, sf->ng) > 0.0f ? sf->ng : -sf->ng);
    float3 e = c - a;
    float len = length(e);
    /* Up to the clip plane: what lies nearer to the camera than znear is not seen (camera_ray). */
    float seen = len - cam->origin[3] / cos_theta;
    if (!(len > 0.0f) || !(seen > 0.0f) || trace_occluded(SCENE_ARGS, a, e / len, seen)) return;
    add_fixed(&splat[3 * pixel], convert_long_sat_rte((double)v.x * splat_scale));
    add_fixed(&splat[3 * pixel + 1], convert_long_sat_rte((double)v.y * splat_scale));
    add_fixed(&splat[3 * pixel + 2], convert_long_sat_rte((double)v.z * splat_scale));
}

/* Light sub-paths [first_path, first_path + num_paths) of the pass: their vertices on non-delta
 * surfaces go to verts (counter counts them; more than capacity: the host grows the buffer and
 * runs the batch again), path_last[i] is sub-path first_path + i's last stored vertex. Paths have
 * at most max_len segments from light to camera. */
__kernel SCALAR_WORK_ITEMS void vcm_light(SCENE_PARAMS, __constant Camera* cam, const VcmPass vp, uint first_path,
                                          uint num_paths, __global LightVertex* verts, uint capacity,
                                          volatile __global uint* counter, __global uint* path_last,
                                          volatile __global long* splat) {
    uint i = get_global_id(0);
    if (i >= num_paths) return;
    uint last = VCM_NO_VERTEX;
    path_last[i] = last;
    if (info->num_lights == 0) return;
    Rng rng = rng_make(vp.seed, vp.pass, first_path + i, RNG_VCM_LIGHT);
    LightEmission e;
    emit_light(SCENE_ARGS, &rng, &e);
    if (!(max3(e.flux) > 0.0f) || !(e.emission_pdf_w > 0.0f)) return;
    /* Densities per unit scene-relative area: an area light's both, the emission density of a light
     * at infinity (over its disc); a point's emission density is per solid angle alone and a light
     * at infinity's direct density per solid angle. */
    float emission_pdf_w = e.finite && e.delta ? e.emission_pdf_w : e.emission_pdf_w * vp.area_scale;
    float direct_pdf_a = e.finite && !e.delta ? e.direct_pdf_a * vp.area_scale : e.direct_pdf_a;
    VcmMis m = vcm_light_start(emission_pdf_w, direct_pdf_a, e.cos_light, e.delta, e.finite, vp.vc_factor);
    const bool store = vcm_uses_connections(vp.mode) || vcm_uses_merging(vp.mode);
    const bool to_camera = vcm_uses_connections(vp.mode) || vp.mode == VCM_MODE_LT;
    float3 T = e.flux, org = e.org, dir = e.dir;
    const PassWavelength pw = pass_wavelength(vp.seed, vp.pass);
    bool dispersed = false; /* the sub-path has met a dispersive surface and carries W (dispersion.cl) */
    for (uint len = 1; len <= vp.max_len; ++len) {
        Hit hit;
        if (!trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit)) break;
        Surface sf = make_surface(SCENE_ARGS, dir, &hit);
        if (HAS_VOLUME) {
            T *= volume_transmittance(SCENE_ARGS, &sf, sf.t * length(dir));
            if (!(max3(T) > 0.0f)) break;
        }
        float3 wo = -dir;
        vcm_on_hit(&m, sf.t * sf.t * dot(dir, dir) / vp.area_scale, fabs(dot(sf.ns, wo)), len == 1 && !e.finite);
        Bsdf b = surface_bsdf(SCENE_ARGS, &sf, TRANSPORT_IMPORTANCE);
        if (HAS_DISPERSION) disperse(SCENE_ARGS, &sf, &b, &pw, &dispersed, &T);
        if (bsdf_has_nondelta(&b)) {
            if (store) {
                uint slot = atomic_inc(counter);
                if (slot < capacity) {
                    __global LightVertex* v = &verts[slot];
                    v->pos[0] = sf.p.x;
                    v->pos[1] = sf.p.y;
                    v->pos[2] = sf.p.z;
                    v->normal_oct = oct_encode(sf.ns);
                    v->throughput[0] = with_dispersed(T.x, dispersed);
                    v->throughput[1] = T.y;
                    v->throughput[2] = T.z;
                    v->wi_oct = oct_encode(wo);
                    v->d_vcm = m.d_vcm;
                    v->d_vc = m.d_vc;
                    v->d_vm = m.d_vm;
                    v->prim = hit.prim;
                    v->u = hit.u;
                    v->v = hit.v;
                    v->prev = last;
                    v->path_length = len;
                    last = slot;
                }
            }
            if (to_camera)
                vcm_connect_to_camera(SCENE_ARGS, cam, &sf, &b, wo, T, &m, vp.light_paths, vp.vm_factor, vp.area_scale,
                                      vp.mode, splat, vp.splat_scale, &rng);
        }
        if (len + 2 > vp.max_len) break; /* a further vertex would need a path longer than max_len */
        BsdfSample s;
        float u0 = rng_float(&rng), u1 = rng_float(&rng), u2 = rng_float(&rng);
        if (!bsdf_sample(&b, wo, LOBE_ALL, u0, u1, u2, &s)) break;
        float rev = s.delta ? 0.0f : bsdf_pdf_rev(&b, wo, s.wi, LOBE_ALL);
        /* Russian roulette by the scattering weight, as photons (kernels/photon_trace.cl). */
        float q = fmin(max3(s.weight), 1.0f);
        if (q < 1.0f && !(rng_float(&rng) < q)) break;
        T *= s.weight / q;
        vcm_on_scatter(&m, fabs(dot(b.ns, s.wi)), s.pdf, rev, s.delta, vp.vm_factor, vp.vc_factor);
        dir = s.wi;
        org = offset_origin(SCENE_ARGS, sf.p, s.below ? -sf.ng : sf.ng);
        if (!(max3(T) > 0.0f)) break;
    }
    path_last[i] = last;
}

/* ---- camera sub-paths ------------------------------------------------------------------------- */

/* s = 1: one light sample at a camera vertex (SmallVCM DirectIllumination), radiance towards wo. */
float3 vcm_light_sample(SCENE_PARAMS, const Surface* sf, const Bsdf* b, float3 wo, const VcmMis* m, float vm_factor,
                        float area_scale, Rng* rng) {
    LightSample ls;
    if (!sample_light_full(SCENE_ARGS, sf->p, rng, &ls)) return (float3)(0.0f);
    if (!bsdf_connects(b, ls.wi, LOBE_ALL)) return (float3)(0.0f);
    float3 f = bsdf_eval(b, wo, ls.wi, LOBE_ALL);
    if (!(max3(f) > 0.0f)) return (float3)(0.0f);
    bool through = dot(ls.wi, b->ns) < 0.0f;
    if (trace_occluded(SCENE_ARGS, offset_origin(SCENE_ARGS, sf->p, through ? -b->ng : b->ng), ls.wi, ls.dist))
        return (float3)(0.0f);
    float cos_x = fabs(dot(ls.wi, b->ns));
    /* emission_pdf_w / pdf_w is per unit area for every kind of light: scene-relative here. */
    float w = vcm_weight_light_sample(m, ls.pdf_w, ls.emission_pdf_w * area_scale, ls.cos_light, ls.delta,
                                      bsdf_pdf(b, wo, ls.wi, LOBE_ALL), bsdf_pdf_rev(b, wo, ls.wi, LOBE_ALL), cos_x,
                                      vm_factor);
    return f * ls.contrib * bsdf_segment_transmittance(b, ls.wi, ls.dist) * (cos_x * w);
}

/* s, t >= 2: the camera vertex at sf (BSDF b, wo, state m) joined to light vertex lv; the light
 * side's part, in units of total power per scene-relative area (SmallVCM ConnectVertices). */
float3 vcm_connect(SCENE_PARAMS, const Surface* sf, const Bsdf* b, float3 wo, const VcmMis* m,
                   __global const LightVertex* lv, float vm_factor, float area_scale, const PassWavelength* pw,
                   bool dispersed) {
    float3 y = load3g(lv->pos);
    float3 d = y - sf->p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return (float3)(0.0f);
    float3 w = d / sqrt(dist2);
    if (!bsdf_connects(b, w, LOBE_ALL)) return (float3)(0.0f);
    float3 f_c = bsdf_eval(b, wo, w, LOBE_ALL);
    if (!(max3(f_c) > 0.0f)) return (float3)(0.0f);
    /* The light vertex's surface and BSDF, rebuilt where it was found. */
    float3 wi_l = oct_decode(lv->wi_oct);
    Hit h;
    h.t = 0.0f;
    h.u = lv->u;
    h.v = lv->v;
    h.prim = lv->prim;
    Surface sl = make_surface(SCENE_ARGS, -wi_l, &h);
    Bsdf bl = surface_bsdf(SCENE_ARGS, &sl, TRANSPORT_IMPORTANCE);
    if (HAS_DISPERSION) disperse_index(SCENE_ARGS, &sl, &bl, pw);
    if (!bsdf_connects(&bl, -w, LOBE_ALL)) return (float3)(0.0f);
    float3 f_l = bsdf_eval(&bl, wi_l, -w, LOBE_ALL);
    if (!(max3(f_l) > 0.0f)) return (float3)(0.0f);
    float cos_c = fabs(dot(b->ns, w)), cos_l = fabs(dot(bl.ns, w));
    float dist2n = dist2 / area_scale;
    VcmMis ml;
    ml.d_vcm = lv->d_vcm;
    ml.d_vc = lv->d_vc;
    ml.d_vm = lv->d_vm;
    float weight = vcm_weight_connection(
        m, &ml, bsdf_pdf(b, wo, w, LOBE_ALL) * cos_l / dist2n, bsdf_pdf_rev(b, wo, w, LOBE_ALL),
        bsdf_pdf(&bl, wi_l, -w, LOBE_ALL) * cos_c / dist2n, bsdf_pdf_rev(&bl, wi_l, -w, LOBE_ALL), vm_factor);
    /* A segment inside a volume is inside it at both ends: absorbed once. */
    float3 v = f_c * f_l * load3_dispersed(lv->throughput) * bsdf_segment_transmittance(b, w, sqrt(dist2)) *
               (weight * cos_c * cos_l / dist2n);
    if (HAS_DISPERSION) v *= merge_dispersion(dispersed, is_dispersed(lv->throughput[0]), pw);
    if (!all(isfinite(v)) || !(max3(v) > 0.0f)) return (float3)(0.0f);
    if (!vcm_visible(SCENE_ARGS, sf->p, sf->ng, y, sl.ng, w)) return (float3)(0.0f);
    return v;
}

/* The MIS weight of emission le found by a camera sub-path after t segments (s = 0), on the
 * surface sf reached along dir, or (sf 0) by a ray that escaped along unit dir. */
float vcm_emission_weight(SCENE_PARAMS, const Surface* sf, float3 dir, uint t, bool specular, const VcmMis* m,
                          uint mode, float area_scale) {
    if (t == 1) return 1.0f; /* seen directly: the only technique for it */
    if (mode == VCM_MODE_PT) return 1.0f;
    if (mode == VCM_MODE_VM) return specular ? 1.0f : 0.0f;
    if (mode == VCM_MODE_LT) return 0.0f;
    float direct, emission;
    if (sf) {
        /* Per scene-relative area: the light sampling's choice of this triangle and point, and its
         * emission into -dir. */
        __global const Material* mat = &materials[sf->material];
        direct = emitter_power_per_area(SCENE_ARGS, sf->prim, sf->material) / info->total_power * area_scale;
        float sides = (mat->flags & MATERIAL_FLAG_DOUBLE_SIDED) ? 2.0f : 1.0f;
        emission = direct * fabs(dot(sf->ng, dir)) / length(dir) * INV_PI_F / sides;
    } else {
        direct = env_light_pdf(SCENE_ARGS, dir);
        emission = direct * area_scale / (PI_F * info->radius * info->radius);
    }
    return vcm_weight_emission(m, direct, emission);
}

/* One camera sub-path per pixel (SmallVCM RunIteration's camera half). batch_flags: 1, this is
 * the pass's first batch of light sub-paths (the camera sub-path's own techniques count); 2, its
 * last (the splat image joins the pixel). The grid holds this batch's light vertices (sorted); verts
 * and path_last hold its sub-paths [batch_first, batch_first + batch_count) as vcm_light left them.
 * A pixel's sample is radiance plus light_unit times the light side and splat_unit times its splats. */
__kernel SCALAR_WORK_ITEMS void vcm_camera(SCENE_PARAMS, __constant Camera* cam, const VcmPass vp, uint pixel_end,
                                           __constant GridInfo* g, __global const LightVertex* sorted,
                                           __global const uint* starts, __global const LightVertex* verts,
                                           __global const uint* path_last, uint batch_first, uint batch_count,
                                           uint batch_flags, __global long* splat, __global double* pass_sum,
                                           __global double* accum) {
    uint p = get_global_id(0);
    if (p >= pixel_end) return; /* the launch covers [offset, pixel_end), padded to the work-group size */
    const bool first = (batch_flags & 1u) != 0u;
    Rng rng = rng_make(vp.seed, vp.pass, p, RNG_VCM_CAMERA);
    Rng rng_ls = rng_make(vp.seed, vp.pass, p, RNG_VCM_LIGHT_SAMPLE);
    float2 off = pixel_sample_offset(0, 1, true, &rng);
    float2 lens = (float2)(rng_float(&rng), rng_float(&rng));
    float3 org, dir;
    camera_ray(cam, (float)(p % cam->width) + off.x, (float)(p / cam->width) + off.y, lens, &org, &dir);
    VcmMis m = vcm_camera_start(camera_pixel_pdf_w(cam, dot(dir, load3c(cam->forward))), vp.light_paths);
    float3 L = (float3)(0.0f), Ll = (float3)(0.0f), beta = (float3)(1.0f);
    long acc0 = 0, acc1 = 0, acc2 = 0; /* merges, fixed point: independent of the grid's order */
    bool specular = true;
    const PassWavelength pw = pass_wavelength(vp.seed, vp.pass);
    bool dispersed = false; /* the sub-path has met a dispersive surface and carries W (dispersion.cl) */
    const bool connections = vcm_uses_connections(vp.mode), merging = vcm_uses_merging(vp.mode);
    const bool in_batch = p >= batch_first && p - batch_first < batch_count;
    const uint lv_last = connections && in_batch ? path_last[p - batch_first] : VCM_NO_VERTEX;
    for (uint t = 1; t <= vp.max_len; ++t) {
        Hit hit;
        if (!trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit)) {
            if (first && HAS_ENV_LIGHT && info->env_light != ENV_UNIFORM) {
                float3 d = normalize(dir);
                float3 le = escaped_radiance(SCENE_ARGS, d, t == 1, true, 0.0f);
                if (max3(le) > 0.0f)
                    L += beta * le * vcm_emission_weight(SCENE_ARGS, 0, d, t, specular, &m, vp.mode, vp.area_scale);
            }
            break;
        }
        Surface sf = make_surface(SCENE_ARGS, dir, &hit);
        if (HAS_VOLUME) beta *= volume_transmittance(SCENE_ARGS, &sf, sf.t * length(dir));
        float3 wo = -dir;
        vcm_on_hit(&m, sf.t * sf.t * dot(dir, dir) / vp.area_scale, fabs(dot(sf.ns, wo)) / length(dir), false);
        if (first) {
            float3 le = surface_emission(SCENE_ARGS, &sf, dir);
            if (max3(le) > 0.0f)
                L += beta * le * vcm_emission_weight(SCENE_ARGS, &sf, dir, t, specular, &m, vp.mode, vp.area_scale);
            if (HAS_UNLIT && specular) L += beta * surface_unlit(SCENE_ARGS, &sf);
        }
        if (t >= vp.max_len) break;
        wo = normalize(wo);
        Bsdf b = surface_bsdf(SCENE_ARGS, &sf, TRANSPORT_RADIANCE);
        if (HAS_DISPERSION) disperse(SCENE_ARGS, &sf, &b, &pw, &dispersed, &beta);
        if (bsdf_has_nondelta(&b)) {
            if (connections && first && t + 1 <= vp.max_len)
                L += beta * vcm_light_sample(SCENE_ARGS, &sf, &b, wo, &m, vp.vm_factor, vp.area_scale, &rng_ls);
            for (uint k = lv_last; k != VCM_NO_VERTEX; k = verts[k].prev) {
                __global const LightVertex* lv = &verts[k];
                if (lv->path_length + t + 1 > vp.max_len) continue;
                Ll += beta * vcm_connect(SCENE_ARGS, &sf, &b, wo, &m, lv, vp.vm_factor, vp.area_scale, &pw, dispersed);
            }
            if (merging) {
                GRID_FOR_EACH_NEAR(g, sorted, starts, sf.p, vp.r2, {
                    if (ph->path_length + t > vp.max_len) continue;
                    float3 wi = oct_decode(ph->wi_oct);
                    /* Light and camera on the same side of the surface (or on either side of rough
                     * glass, which the BSDF decides). */
                    if ((dot(b.ns, wi) > 0.0f) != (dot(b.ns, oct_decode(ph->normal_oct)) > 0.0f)) continue;
                    float3 f = bsdf_eval(&b, wo, wi, LOBE_ALL);
                    if (!(max3(f) > 0.0f)) continue;
                    float w = 1.0f;
                    if (vp.mode != VCM_MODE_VM) {
                        VcmMis ml;
                        ml.d_vcm = ph->d_vcm;
                        ml.d_vc = ph->d_vc;
                        ml.d_vm = ph->d_vm;
                        w = vcm_weight_merge(&m, &ml, bsdf_pdf(&b, wo, wi, LOBE_ALL),
                                             bsdf_pdf_rev(&b, wo, wi, LOBE_ALL), vp.vc_factor);
                    }
                    float3 c = beta * f * load3_dispersed(ph->throughput) * w;
                    if (HAS_DISPERSION) c *= merge_dispersion(dispersed, is_dispersed(ph->throughput[0]), &pw);
                    if (!all(isfinite(c))) continue;
                    acc0 += convert_long_sat_rte((double)c.x * FLUX_FIXED_SCALE);
                    acc1 += convert_long_sat_rte((double)c.y * FLUX_FIXED_SCALE);
                    acc2 += convert_long_sat_rte((double)c.z * FLUX_FIXED_SCALE);
                });
                if (vp.mode == VCM_MODE_VM) break; /* PPM: merge at the first non-delta vertex only */
            }
        }
        BsdfSample s;
        float u0 = rng_float(&rng), u1 = rng_float(&rng), u2 = rng_float(&rng);
        if (!bsdf_sample(&b, wo, LOBE_ALL, u0, u1, u2, &s)) break;
        float rev = s.delta ? 0.0f : bsdf_pdf_rev(&b, wo, s.wi, LOBE_ALL);
        /* Russian roulette after the first bounces, survival by throughput (as the path tracer). */
        if (t >= 3) {
            float q = fmin(max3(beta * s.weight), 1.0f);
            if (!(rng_float(&rng) < q)) break;
            beta *= s.weight / q;
        } else {
            beta *= s.weight;
        }
        vcm_on_scatter(&m, fabs(dot(b.ns, s.wi)), s.pdf, rev, s.delta, vp.vm_factor, vp.vc_factor);
        specular = specular && s.delta;
        dir = s.wi;
        org = offset_origin(SCENE_ARGS, sf.p, s.below ? -sf.ng : sf.ng);
        if (!(max3(beta) > 0.0f)) break;
    }
    /* Never let one bad sample poison a pixel. */
    if (!all(isfinite(L))) L = (float3)(0.0f);
    if (!all(isfinite(Ll))) Ll = (float3)(0.0f);
    double r0 = (double)L.x + vp.light_unit * ((double)Ll.x + (double)acc0 * (vp.vm_norm / FLUX_FIXED_SCALE));
    double r1 = (double)L.y + vp.light_unit * ((double)Ll.y + (double)acc1 * (vp.vm_norm / FLUX_FIXED_SCALE));
    double r2_ = (double)L.z + vp.light_unit * ((double)Ll.z + (double)acc2 * (vp.vm_norm / FLUX_FIXED_SCALE));
    /* This batch's splats (light tracing) join the pixel (the host clears them before each batch). */
    r0 += (double)splat[3 * p] * vp.splat_unit;
    r1 += (double)splat[3 * p + 1] * vp.splat_unit;
    r2_ += (double)splat[3 * p + 2] * vp.splat_unit;
    /* Batches add up in pass_sum; the last one adds the pass to the running sum (an abandoned pass
     * leaves accum as the last whole pass left it). */
    if (!first) {
        r0 += pass_sum[3 * p];
        r1 += pass_sum[3 * p + 1];
        r2_ += pass_sum[3 * p + 2];
    }
    __global double* out = (batch_flags & 2u) ? accum : pass_sum;
    if (batch_flags & 2u) {
        out[3 * p] += r0;
        out[3 * p + 1] += r1;
        out[3 * p + 2] += r2_;
    } else {
        out[3 * p] = r0;
        out[3 * p + 1] = r1;
        out[3 * p + 2] = r2_;
    }
}

/* Pixel footprints at the first surfaces (pixel centre rays): the distance times the angle one
 * pixel subtends, -1 where the ray leaves the scene (the initial merging radius, as SPPM's). */
__kernel SCALAR_WORK_ITEMS void vcm_footprint(SCENE_PARAMS, __constant Camera* cam, uint num_pixels,
                                              __global float* out) {
    uint p = get_global_id(0);
    if (p >= num_pixels) return;
    float3 org, dir;
    camera_ray(cam, (float)(p % cam->width) + 0.5f, (float)(p / cam->width) + 0.5f, (float2)(0.5f, 0.5f), &org, &dir);
    Hit hit;
    out[p] = trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit) ? camera_footprint(cam, hit.t) : -1.0f;
}
