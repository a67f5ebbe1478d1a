/* medium.cl: homogeneous participating media: the world's (SceneInfo.medium_*), filling space
 * outside the closed volumes with the camera inside it, and a closed mesh's own where its material
 * scatters (Material.scatter): extinction sigma_t, single-scattering albedo sigma_s / sigma_t per
 * RGB channel, and the Henyey-Greenstein phase function.
 *
 * Which medium a segment runs in is told by the surface it ends on (the paths need no stack): a
 * segment that reaches the back face of a mesh whose material encloses a volume
 * (MATERIAL_FLAG_ENCLOSES_VOLUME: transmission with KHR_materials_volume) ran inside that mesh, in
 * the mesh's own medium where KHR_materials_volume_scatter makes it scatter (material_medium) and
 * through its absorption alone elsewhere (scene.cl volume_transmittance); every other segment ran
 * in the volume the mesh it ends on lies in (Material.outside, found on the host by
 * src/scene/volume_nesting.h), and one that leaves the scene in the world's medium. A light sample
 * or a connection from a surface runs inside the mesh when it leaves through the face towards
 * the inside, else in the volume the mesh lies in (leaving_volume). So a glass sphere in fog, an
 * absorbing mesh in fog, a fog cube with objects and lights in it and a medium inside a medium
 * each hold their own volumes; meshes are taken as closed, and crossing meshes are not nested.
 *
 * Distances are sampled in proportion to sigma_t T with one channel picked in proportion to the
 * path's throughput, and weighted by the one-sample balance heuristic over the three channels
 * (the spectral MIS of Mitsuba 3's volpath and of pbrt-v4, in RGB): unbiased for chromatic media,
 * with weights bounded by 1 / (the picked channel's probability) where the channels differ. */
#ifndef CLPPM_MEDIUM_CL
#define CLPPM_MEDIUM_CL

#include "scene.cl"

/* A homogeneous medium: extinction, single-scattering albedo, Henyey-Greenstein g, and which it
 * is (MEDIUM_WORLD, or the enclosing mesh's material index plus one): photons stored in one medium
 * are gathered only by volume hit points and beams in the same (gather_query.cl), so that a
 * radius does not blur one medium's light into its neighbour's across their boundary. */
typedef struct {
    float3 sigma_t, albedo;
    float g;
    uint id;
} Medium;

#define MEDIUM_WORLD 0u

/* Whether the scene has a world medium (a program built for scenes without one says no at once). */
bool world_has_medium(__constant SceneInfo* info) { return HAS_MEDIUM && info->medium_sigma_t[3] != 0.0f; }

float3 world_sigma_t(__constant SceneInfo* info) { return load3c(info->medium_sigma_t); }

Medium world_medium(__constant SceneInfo* info) {
    Medium m;
    m.sigma_t = load3c(info->medium_sigma_t);
    m.albedo = load3c(info->medium_albedo);
    m.g = info->medium_albedo[3];
    m.id = MEDIUM_WORLD;
    return m;
}

/* Whether material m's volume scatters (KHR_materials_volume_scatter; shared_types.h Material.scatter). */
bool material_scatters(__global const Material* m) {
    return HAS_MEDIUM && (m->scatter[0] > 0.0f || m->scatter[1] > 0.0f || m->scatter[2] > 0.0f);
}

/* The medium inside a mesh of material `index`, m: its attenuation is the extinction. */
Medium material_medium(__global const Material* m, uint index) {
    Medium r;
    r.sigma_t = load3g(m->attenuation);
    r.albedo = load3g(m->scatter);
    r.g = m->scatter[3];
    r.id = index + 1u;
    return r;
}

/* exp(-sigma t) per channel, 1 in channels without extinction (t may be INFINITY). */
float3 medium_transmittance(float3 sigma, float t) {
    return (float3)(sigma.x > 0.0f ? exp(-sigma.x * t) : 1.0f, sigma.y > 0.0f ? exp(-sigma.y * t) : 1.0f,
                    sigma.z > 0.0f ? exp(-sigma.z * t) : 1.0f);
}

/* Which closed volume a segment along dir that ends at the hit h ran in: the mesh's own (its
 * material's index + 1) where it ends on the back face of a mesh that encloses a volume, else the
 * one that mesh lies in (Material.outside, src/scene/volume_nesting.h; MEDIUM_WORLD: the world's).
 * From the hit alone, so that a path that scatters before the surface never builds it. */
uint segment_volume(SCENE_PARAMS, float3 dir, const Hit* h) {
    const uint index = shading[h->prim].material;
    __global const Material* m = &materials[index];
    if ((m->flags & MATERIAL_FLAG_ENCLOSES_VOLUME) &&
        dot(cross(tris[3 * h->prim + 1].xyz, tris[3 * h->prim + 2].xyz), dir) >= 0.0f) /* its back face */
        return index + 1u;
    return m->outside;
}

/* Which closed volume a straight segment that leaves the surface sf along w runs in (as
 * segment_volume tells it). */
uint leaving_volume(SCENE_PARAMS, const Surface* sf, float3 w) {
    __global const Material* m = &materials[sf->material];
    if ((m->flags & MATERIAL_FLAG_ENCLOSES_VOLUME) && (sf->front ? dot(w, sf->ng) < 0.0f : dot(w, sf->ng) > 0.0f))
        return sf->material + 1u;
    return m->outside;
}

/* The medium of volume v (segment_volume): the world's, or the scattering medium of a closed mesh
 * (*inside). False where there is none to sample: a clear world, or a mesh that only absorbs (its
 * toll is taken at the surface, scene.cl volume_transmittance). */
bool volume_medium(SCENE_PARAMS, uint v, Medium* m, bool* inside) {
    *inside = false;
    if (v == MEDIUM_WORLD) {
        if (!world_has_medium(info)) return false;
        *m = world_medium(info);
        return true;
    }
    __global const Material* mat = &materials[v - 1u];
    if (!material_scatters(mat)) return false;
    *m = material_medium(mat, v - 1u);
    *inside = true;
    return true;
}

/* The medium a segment along dir ran in, ending at the hit h (found) or leaving the scene (the
 * world's): volume_medium of its segment_volume. The one rule of every path (the header). */
bool segment_medium(SCENE_PARAMS, bool found, float3 dir, const Hit* h, Medium* m, bool* inside) {
    return volume_medium(SCENE_ARGS, found ? segment_volume(SCENE_ARGS, dir, h) : MEDIUM_WORLD, m, inside);
}

/* The extinction along a straight segment in volume v: the world's medium's, or a mesh's
 * attenuation (absorbing or scattering); 0 where v is clear. */
float3 volume_sigma_t(SCENE_PARAMS, uint v) {
    if (v == MEDIUM_WORLD) return world_has_medium(info) ? world_sigma_t(info) : (float3)(0.0f);
    return load3g(materials[v - 1u].attenuation);
}

/* The Henyey-Greenstein phase function (Henyey and Greenstein 1941; pbrt-v4 Sec. 11.3.1) at the
 * cosine between the direction light travelled in and the one it leaves in:
 * p = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^(3/2)), g > 0 forwards. */
float hg_phase(float cos_theta, float g) {
    float denom = 1.0f + g * g - 2.0f * g * cos_theta;
    return (1.0f - g * g) / (4.0f * M_PI_F * denom * sqrt(fmax(denom, 0.0f)));
}

/* A direction from the phase function about d (the direction light travelled in), by inverting
 * its distribution of cos theta; *pdf its density, the phase function itself. */
float3 hg_sample(float3 d, float g, float2 u, float* pdf) {
    float cos_t;
    if (fabs(g) < 1e-3f) {
        cos_t = 1.0f - 2.0f * u.x;
    } else {
        float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u.x);
        cos_t = (1.0f + g * g - s * s) / (2.0f * g);
    }
    cos_t = clamp(cos_t, -1.0f, 1.0f);
    float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t));
    float2 c = unit_circle(u.y);
    float3 t, b;
    make_frame(d, &t, &b);
    *pdf = hg_phase(cos_t, g);
    return normalize(t * (sin_t * c.x) + b * (sin_t * c.y) + d * cos_t);
}

/* The probabilities of the channel that picks a free flight's distance: in proportion to the
 * path's throughput beta (uniform when it is black). */
float3 medium_channel_pick(float3 beta) {
    float3 b = fabs(beta);
    float sum = b.x + b.y + b.z;
    return sum > 0.0f ? b / sum : (float3)(1.0f / 3.0f);
}

/* The extinction of the channel the uniform u picks with probabilities pc (medium_channel_pick). */
float medium_picked_sigma(float3 sigma, float3 pc, float u) {
    return u < pc.x || pc.y + pc.z == 0.0f ? sigma.x : u < pc.x + pc.y || pc.z == 0.0f ? sigma.y : sigma.z;
}

/* The density of a free flight from a path of throughput beta scattering at distance t:
 * sum over the channels of their pick times sigma_t T(t). */
float medium_distance_pdf(const Medium* m, float3 beta, float t) {
    return dot(medium_channel_pick(beta), m->sigma_t * medium_transmittance(m->sigma_t, t));
}

/* Equiangular sampling (Kulla and Fajardo 2012, "Importance Sampling Techniques for Path Tracing
 * in Participating Media", Sec. 4): a distance along the ray o + t d, t in [0, t_max), in
 * proportion to 1 / r^2 towards the point c, by the angle theta the point subtends:
 * t = delta + D tan(theta), theta uniform in [theta_a, theta_b], pdf = D / ((theta_b - theta_a)(D^2
 * + (t - delta)^2)), with delta the foot of c on the ray and D its distance from it. Returns false
 * where c lies on the ray's line (no angle to sample). */
bool equiangular_sample(float3 o, float3 d, float t_max, float3 c, float u, float* t, float* pdf) {
    float3 oc = c - o;
    float delta = dot(oc, d);
    float D = length(oc - delta * d);
    if (!(D > 1e-6f * (fabs(delta) + length(oc)))) return false;
    float th_a = atan2(-delta, D), th_b = atan2(t_max - delta, D); /* atan2(inf, D) = pi / 2 */
    if (!(th_b > th_a)) return false;
    float th = th_a + u * (th_b - th_a);
    *t = fmax(delta + D * tan(th), 0.0f);
    float x = *t - delta;
    *pdf = D / ((th_b - th_a) * (D * D + x * x));
    return *t < t_max;
}

/* equiangular_sample's density at t. */
float equiangular_pdf(float3 o, float3 d, float t_max, float3 c, float t) {
    float3 oc = c - o;
    float delta = dot(oc, d);
    float D = length(oc - delta * d);
    if (!(D > 1e-6f * (fabs(delta) + length(oc)))) return 0.0f;
    float th_a = atan2(-delta, D), th_b = atan2(t_max - delta, D);
    if (!(th_b > th_a)) return 0.0f;
    float x = t - delta;
    return D / ((th_b - th_a) * (D * D + x * x));
}

/* A distance in [0, t_max), t_max finite, in proportion to sigma_t T in one channel of extinction
 * sigma (uniform where sigma is 0): the exponential truncated to the segment. Its density at t. */
float truncated_distance_pdf(float sigma, float t_max, float t) {
    return sigma > 0.0f ? sigma * exp(-sigma * t) / -expm1(-sigma * t_max) : 1.0f / t_max;
}

/* A distance within [0, t_max) in the medium m, from the uniforms u (x: the channel, y: the
 * distance): truncated_distance_pdf in one channel picked in proportion to beta, weighted by the
 * one-sample balance heuristic over the channels as medium_sample_distance is. Every sample lands
 * in the segment (a beam's light samples, kernels/beam.cl). Returns the distance and *beta times
 * sigma_t T / pdf; false where the pdf vanishes (beta is then 0). */
bool medium_sample_within(const Medium* m, float t_max, float2 u, float3* beta, float* t) {
    const float3 sigma = m->sigma_t, pc = medium_channel_pick(*beta);
    const float s = medium_picked_sigma(sigma, pc, u.x);
    *t = fmin(s > 0.0f ? -log1p(u.y * expm1(-s * t_max)) / s : u.y * t_max, t_max);
    const float pdf = pc.x * truncated_distance_pdf(sigma.x, t_max, *t) +
                      pc.y * truncated_distance_pdf(sigma.y, t_max, *t) +
                      pc.z * truncated_distance_pdf(sigma.z, t_max, *t);
    *beta = pdf > 0.0f ? *beta * (sigma * medium_transmittance(sigma, *t)) / pdf : (float3)(0.0f);
    return pdf > 0.0f;
}

/* One free-flight distance along a segment of length t_max (INFINITY: to the end of the world)
 * in the medium m, from the uniforms u (x: the channel, y: the distance). Returns true with the
 * collision's distance in *t and *beta times sigma_t T / pdf (the albedo, which a scattering there
 * takes, is the caller's: photons store the flux that arrives), or false with *beta times
 * T(t_max) / P(no event before t_max). */
bool medium_sample_distance(const Medium* m, float t_max, float2 u, float3* beta, float* t) {
    float3 sigma = m->sigma_t;
    float3 pc = medium_channel_pick(*beta);
    float s = medium_picked_sigma(sigma, pc, u.x);
    float ts = s > 0.0f ? -log1p(-u.y) / s : INFINITY;
    if (ts < t_max) {
        float3 T = medium_transmittance(sigma, ts);
        float pdf = dot(pc, sigma * T);
        *beta = pdf > 0.0f ? *beta * (sigma * T) / pdf : (float3)(0.0f);
        *t = ts;
        return true;
    }
    float3 T = medium_transmittance(sigma, t_max);
    float p = dot(pc, T);
    *beta = p > 0.0f ? *beta * T / p : (float3)(0.0f);
    return false;
}

#endif
