/* vcm_mis.h: the multiple importance sampling weights of vertex connection and merging
 * (Georgiev, Krivanek, Davidovic, Slusallek 2012, "Light transport simulation with vertex
 * connection and merging", and its technical report "Implementing vertex connection and merging",
 * Eqs. 31-39), in the recursive form of SmallVCM (vertexcm.hxx): each sub-path carries three
 * partial sums, d_vcm, d_vc and d_vm, updated at every vertex, from which every technique's weight
 * follows in O(1). Shared by the kernels (kernels/vcm.cl) and the host test that checks them
 * against the closed form on enumerated paths (tests/vcm_mis_test.cpp), so both run this code.
 *
 * Techniques, over a path of k segments: s = 0 (a camera path finds emission), s = 1 (the camera
 * path samples a light: next-event estimation), t = 1 (a light vertex connects to the camera:
 * light tracing), s, t >= 2 (a camera vertex connects to a light vertex), and merging a light
 * vertex into a camera vertex within radius r. eta_vcm = pi r^2 N_L, with N_L light sub-paths per
 * pass, relates merging's density to a connection's. The heuristic is the power heuristic
 * (beta = 2): vcm_mis(p) = p^2.
 *
 * Densities: *_pdf_w per unit solid angle, *_pdf_a per unit area; "dir" is the density of the
 * sub-path's own sampling direction, "rev" of the opposite one. Russian roulette is left out of
 * every density (as pbrt-v4's BDPT does): any weights that sum to one keep the estimate unbiased. */
#ifndef CLPPM_VCM_MIS_H
#define CLPPM_VCM_MIS_H

#ifdef __OPENCL_VERSION__
#define VCM_FN
#else
#define VCM_FN inline
#endif

/* The techniques a render uses (--integrator vcm and bpt, and the single-technique modes the tests
 * compare). */
#define VCM_MODE_VCM 0u /* everything, MIS-weighted */
#define VCM_MODE_BPT 1u /* connections only: s = 0, s = 1, t = 1, s,t >= 2 */
#define VCM_MODE_PT 2u  /* camera paths finding emission, weight 1 (no light sampling) */
#define VCM_MODE_LT 3u  /* light vertices connected to the camera, weight 1 */
#define VCM_MODE_VM                                                                                                    \
    4u /* merging at the first non-delta camera vertex, weight 1 (PPM with eta's
                         * radius; emission only through delta chains from the camera) */

typedef struct {
    float d_vcm, d_vc, d_vm;
} VcmMis;

VCM_FN float vcm_mis(float p) { return p * p; }

/* A light sub-path leaving its light (tech. rep. Eqs. 31-33): the densities of emit_light. */
VCM_FN VcmMis vcm_light_start(float emission_pdf_w, float direct_pdf_a, float cos_light, bool delta, bool finite,
                              float vc_factor) {
    VcmMis m;
    m.d_vcm = vcm_mis(direct_pdf_a / emission_pdf_w);
    m.d_vc = delta ? 0.0f : vcm_mis((finite ? cos_light : 1.0f) / emission_pdf_w);
    m.d_vm = m.d_vc * vc_factor;
    return m;
}

/* A camera sub-path leaving the camera with solid-angle density camera_pdf_w (one pixel's), N_L
 * light sub-paths per pass. */
VCM_FN VcmMis vcm_camera_start(float camera_pdf_w, float light_paths) {
    VcmMis m;
    m.d_vcm = vcm_mis(light_paths / camera_pdf_w);
    m.d_vc = 0.0f;
    m.d_vm = 0.0f;
    return m;
}

/* A sub-path reaches a surface at squared distance dist2, |cos| cos_in there with the direction it
 * came from. from_infinity: the first segment of a light sub-path from a light at infinity (no
 * distance term). */
VCM_FN void vcm_on_hit(VcmMis* m, float dist2, float cos_in, bool from_infinity) {
    if (!from_infinity) m->d_vcm *= vcm_mis(dist2);
    float c = vcm_mis(cos_in);
    m->d_vcm /= c;
    m->d_vc /= c;
    m->d_vm /= c;
}

/* The sub-path scatters into a direction with |cos| cos_out, sampled with density pdf_dir (a
 * non-delta lobe) whose reverse density is pdf_rev; or through a delta lobe (delta). */
VCM_FN void vcm_on_scatter(VcmMis* m, float cos_out, float pdf_dir, float pdf_rev, bool delta, float vm_factor,
                           float vc_factor) {
    if (delta) {
        m->d_vcm = 0.0f;
        m->d_vc *= vcm_mis(cos_out);
        m->d_vm *= vcm_mis(cos_out);
        return;
    }
    float g = vcm_mis(cos_out / pdf_dir);
    float d_vc = g * (m->d_vc * vcm_mis(pdf_rev) + m->d_vcm + vm_factor);
    float d_vm = g * (m->d_vm * vcm_mis(pdf_rev) + m->d_vcm * vc_factor + 1.0f);
    m->d_vc = d_vc;
    m->d_vm = d_vm;
    m->d_vcm = vcm_mis(1.0f / pdf_dir);
}

/* s = 0: a camera sub-path (state c) finds emission whose direct-sampling density (per area, or
 * per solid angle at infinity) is direct_pdf_a and emission density emission_pdf_w (both with
 * the pick probability). Tech. rep. Eq. 41 (SmallVCM GetLightRadiance). */
VCM_FN float vcm_weight_emission(const VcmMis* c, float direct_pdf_a, float emission_pdf_w) {
    float w_camera = vcm_mis(direct_pdf_a) * c->d_vcm + vcm_mis(emission_pdf_w) * c->d_vc;
    return 1.0f / (1.0f + w_camera);
}

/* s = 1: a light sample (LightSample: pdf_w, emission_pdf_w, cos_light, delta) at a camera vertex
 * whose BSDF samples the light's direction with bsdf_dir_pdf_w and the camera's with
 * bsdf_rev_pdf_w; cos_x at the camera vertex. Tech. rep. Eq. 44 (SmallVCM DirectIllumination). */
VCM_FN float vcm_weight_light_sample(const VcmMis* c, float light_pdf_w, float emission_pdf_w, float cos_light,
                                     bool light_delta, float bsdf_dir_pdf_w, float bsdf_rev_pdf_w, float cos_x,
                                     float vm_factor) {
    float w_light = light_delta ? 0.0f : vcm_mis(bsdf_dir_pdf_w / light_pdf_w);
    float w_camera = vcm_mis(emission_pdf_w * cos_x / (light_pdf_w * cos_light)) *
                     (vm_factor + c->d_vcm + c->d_vc * vcm_mis(bsdf_rev_pdf_w));
    return 1.0f / (w_light + 1.0f + w_camera);
}

/* t = 1: a light vertex (state l) connected to the camera, whose pixel samples it with area density
 * camera_pdf_a; bsdf_rev_pdf_w: the light vertex's BSDF sampling the direction the light arrived
 * from, given the camera's. Tech. rep. Eq. 46 (SmallVCM ConnectToCamera). */
VCM_FN float vcm_weight_camera_connection(const VcmMis* l, float camera_pdf_a, float light_paths, float bsdf_rev_pdf_w,
                                          float vm_factor) {
    float w_light = vcm_mis(camera_pdf_a / light_paths) * (vm_factor + l->d_vcm + l->d_vc * vcm_mis(bsdf_rev_pdf_w));
    return 1.0f / (w_light + 1.0f);
}

/* s, t >= 2: camera vertex (state c) to light vertex (state l). cam_dir_pdf_a: the camera vertex's
 * BSDF sampling the light vertex, per area there; light_dir_pdf_a the reverse; cam_rev_pdf_w and
 * light_rev_pdf_w: each vertex's BSDF sampling its own sub-path's previous direction given the
 * connection. Tech. rep. Eq. 40 (SmallVCM ConnectVertices). */
VCM_FN float vcm_weight_connection(const VcmMis* c, const VcmMis* l, float cam_dir_pdf_a, float cam_rev_pdf_w,
                                   float light_dir_pdf_a, float light_rev_pdf_w, float vm_factor) {
    float w_light = vcm_mis(cam_dir_pdf_a) * (vm_factor + l->d_vcm + l->d_vc * vcm_mis(light_rev_pdf_w));
    float w_camera = vcm_mis(light_dir_pdf_a) * (vm_factor + c->d_vcm + c->d_vc * vcm_mis(cam_rev_pdf_w));
    return 1.0f / (w_light + 1.0f + w_camera);
}

/* Merging a light vertex (state l) into a camera vertex (state c): cam_dir_pdf_w, the camera
 * vertex's BSDF sampling the light's arrival direction; cam_rev_pdf_w, the camera's direction given
 * that. Tech. rep. Eqs. 37-39 (SmallVCM RangeQuery). */
VCM_FN float vcm_weight_merge(const VcmMis* c, const VcmMis* l, float cam_dir_pdf_w, float cam_rev_pdf_w,
                              float vc_factor) {
    float w_light = l->d_vcm * vc_factor + l->d_vm * vcm_mis(cam_dir_pdf_w);
    float w_camera = c->d_vcm * vc_factor + c->d_vm * vcm_mis(cam_rev_pdf_w);
    return 1.0f / (w_light + 1.0f + w_camera);
}

#endif
