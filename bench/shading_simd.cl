/* shading_simd.cl: kernels of bench/shading_simd.cpp, appended to kernels/path_trace.cl (whose
 * scene, surface, BSDF and light code they call). They time one path vertex's shading (no ray
 * traced) from stored camera hits: what the path tracer's megakernel does between traversals.
 * Measurement only; the renderer never runs them. */

/* The pixel centres' camera hits, stored structure-of-arrays: t, u, v, prim, dir x, y, z (n each).
 * A miss keeps prim 0 and the barycentrics (1/3, 1/3) so that every lane shades a real triangle;
 * `hits` counts the real hits. */
__kernel void simd_probe_hits(SCENE_PARAMS, __constant Camera* cam, uint n, __global float* soa,
                              volatile __global uint* hits) {
    uint i = get_global_id(0);
    if (i >= n) return;
    float3 org, dir;
    camera_ray(cam, (float)(i % cam->width) + 0.5f, (float)(i / cam->width) + 0.5f, (float2)(0.5f), &org, &dir);
    Hit hit;
    bool ok = trace_closest(SCENE_ARGS, org, dir, INFINITY, &hit);
    if (ok) atomic_inc(hits);
    soa[i] = ok ? hit.t : 1.0f;
    soa[n + i] = ok ? hit.u : 1.0f / 3.0f;
    soa[2 * n + i] = ok ? hit.v : 1.0f / 3.0f;
    ((__global uint*)soa)[3 * n + i] = ok ? hit.prim : 0u;
    soa[4 * n + i] = dir.x;
    soa[5 * n + i] = dir.y;
    soa[6 * n + i] = dir.z;
}

/* A 32-bit hash of (pixel, pass, k) to a uniform in [0, 1): the same numbers for a pixel whatever
 * the kernel's width. */
inline uint simd_probe_hash(uint pixel, uint pass) {
    uint h = pixel * 0x9E3779B9u ^ (pass * 0x85EBCA6Bu);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

/* The renderer's own code for one vertex, one work item per path: the surface, its BSDF, a light
 * sample weighed by MIS (its shadow ray left out) and the BSDF sample that continues the path. */
__kernel void simd_probe_renderer(SCENE_PARAMS, __global const float* soa, uint n, uint pass, __global float* out) {
    uint i = get_global_id(0);
    Hit hit;
    hit.t = soa[i];
    hit.u = soa[n + i];
    hit.v = soa[2 * n + i];
    hit.prim = ((__global const uint*)soa)[3 * n + i];
    float3 dir = (float3)(soa[4 * n + i], soa[5 * n + i], soa[6 * n + i]);
    uint h = simd_probe_hash(i, pass);
    float u0 = (float)(h >> 8) * 0x1.0p-24f;
    h = h * 0x9E3779B9u ^ (h >> 16);
    float u1 = (float)(h >> 8) * 0x1.0p-24f;
    h = h * 0x9E3779B9u ^ (h >> 16);
    float u2 = (float)(h >> 8) * 0x1.0p-24f;
    h = h * 0x9E3779B9u ^ (h >> 16);
    float u3 = (float)(h >> 8) * 0x1.0p-24f;
    Surface sf = make_surface(SCENE_ARGS, dir, &hit);
    float3 le = surface_emission(SCENE_ARGS, &sf, dir);
    Bsdf b = surface_bsdf(SCENE_ARGS, &sf, TRANSPORT_RADIANCE);
    float3 wo = -dir;
    LightSample ls;
    bool ok = sample_light_reuse(SCENE_ARGS, sf.p, 1.0f, (float2)(u0, u1), u2, &ls);
    float3 wi, contrib;
    float dist, light_pdf;
    light_sample_out(&ls, &wi, &dist, &contrib, &light_pdf);
    float3 f = (float3)(0.0f);
    if (ok && bsdf_connects(&b, wi, LOBE_ALL))
        f = bsdf_eval(&b, wo, wi, LOBE_ALL) * contrib * fabs(dot(wi, b.ns)) *
            power_heuristic(light_pdf, bsdf_pdf(&b, wo, wi, LOBE_ALL));
    BsdfSample s;
    bool ok2 = bsdf_sample(&b, wo, LOBE_ALL, u1, u2, u3, &s);
    float3 o = offset_origin(SCENE_ARGS, sf.p, s.below ? -sf.ng : sf.ng);
    float3 next = ok2 ? s.wi * s.weight : (float3)(0.0f);
    out[i] += f.x + le.x + next.x + o.x + dist;
    out[n + i] += f.y + le.y + next.y + o.y;
    out[2 * n + i] += f.z + le.z + next.z + o.z;
}
