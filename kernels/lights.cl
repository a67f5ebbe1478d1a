/* lights.cl: choosing a light in proportion to power, emitting photons from it, and sampling it
 * for direct lighting. Photon flux is expressed in units of SceneInfo.total_power: a photon that
 * picks light l with probability power_l / P carries P * (Le / mean(Le)) for uniform emitters. */
#ifndef CLPPM_LIGHTS_CL
#define CLPPM_LIGHTS_CL

#include "scene.cl"
#include "environment.cl"

/* light_cdf holds num_lights + 1 increasing values from 0 to 1. */
uint pick_light(SCENE_PARAMS, float u) {
    uint lo = 0, hi = info->num_lights; /* invariant: cdf[lo] <= u < cdf[hi] */
    while (hi - lo > 1) {
        uint mid = (lo + hi) >> 1;
        if (light_cdf[mid] <= u) lo = mid;
        else hi = mid;
    }
    return lo;
}

float light_pick_pdf(SCENE_PARAMS, uint l) { return lights[l].power / info->total_power; }

/* glTF KHR_lights_punctual spot attenuation: a squared linear ramp in cos between the cones. */
float spot_falloff(__global const Light* L, float cos_theta) {
    float scale = 1.0f / fmax(1e-3f, L->cos_inner - L->cos_outer);
    float a = clamp((cos_theta - L->cos_outer) * scale, 0.0f, 1.0f);
    return a * a;
}

/* A uniform point on an emissive triangle, its winding normal and the radiance it emits there
 * (the material's emission times its emissive texture). */
float3 area_light_point(SCENE_PARAMS, __global const Light* L, float2 u, float3* n, float3* le) {
    float3 v0 = tris[3 * L->prim].xyz, e1 = tris[3 * L->prim + 1].xyz, e2 = tris[3 * L->prim + 2].xyz;
    float2 b = sample_triangle(u.x, u.y);
    *n = normalize(cross(e1, e2));
    *le = load3g(L->radiance);
    if (HAS_TEXTURES) {
        *le = material_emission(SCENE_ARGS, shading[L->prim].material, triangle_uv(SCENE_ARGS, L->prim, b.x, b.y));
    }
    return v0 + e1 * b.x + e2 * b.y;
}

/* Power per unit area with which the lights are chosen, for a uniform emitter of radiance le:
 * mean(Le) pi per emitting side (src/scene/device_scene.cpp), so the area cancels and a
 * triangle hit by a ray needs no light index. */
float uniform_power_per_area(float3 le, bool two_sided) {
    return (le.x + le.y + le.z) * (1.0f / 3.0f) * PI_F * (two_sided ? 2.0f : 1.0f);
}

/* The same for the emissive triangle prim of material `material` wherever a ray finds it: for a
 * textured emitter the host's integral of its texture (Light.power / area), found by binary
 * search over the area lights (lights[0, num_emissive_tris), in increasing prim); 0 when the
 * triangle is no light (its texture is black). */
float emitter_power_per_area(SCENE_PARAMS, uint prim, uint material) {
    __global const Material* m = &materials[material];
    if (HAS_TEXTURES && m->emissive_tex >= 0) {
        uint lo = 0, hi = info->num_emissive_tris;
        while (lo < hi) {
            uint mid = (lo + hi) >> 1;
            if (lights[mid].prim < prim) lo = mid + 1;
            else hi = mid;
        }
        if (lo == info->num_emissive_tris || lights[lo].prim != prim) return 0.0f;
        return lights[lo].power / lights[lo].area;
    }
    return uniform_power_per_area(load3g(m->emission), (m->flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u);
}

/* Everything a light sub-path needs of where and how it leaves its light: origin, direction,
 * flux (units of total power, as photons carry it), and the densities of vertex connection and
 * merging (SmallVCM's Light::Emit; Georgiev et al. 2012, tech. rep. Sec. 4): emission_pdf_w, the
 * density of (point, direction) per unit area and solid angle, and direct_pdf_a, of the point
 * alone as direct light sampling would draw it (per unit area, or 1 for a delta position; per
 * unit solid angle for lights at infinity), both times the light's pick probability; cos_light
 * at the light (1 for punctual and infinite lights); delta: no ray can hit it; finite: not at
 * infinity. */
typedef struct {
    float3 org, dir, flux;
    float emission_pdf_w, direct_pdf_a, cos_light;
    bool delta, finite;
} LightEmission;

/* Emits one photon, filling e (flux zero when nothing was emitted). For area lights the
 * direction is cosine-distributed about the emitting side's normal. */
void emit_light(SCENE_PARAMS, Rng* rng, LightEmission* e) {
    uint l = pick_light(SCENE_ARGS, rng_float(rng));
    __global const Light* L = &lights[l];
    float pick = light_pick_pdf(SCENE_ARGS, l);
    float3 rad = load3g(L->radiance);
    e->org = e->dir = e->flux = (float3)(0.0f);
    e->emission_pdf_w = e->direct_pdf_a = 0.0f;
    e->cos_light = 1.0f;
    e->delta = true;
    e->finite = true;
    if (HAS_AREA_LIGHTS && L->type == LIGHT_TRIANGLE) {
        float3 n;
        float u0 = rng_float(rng), u1 = rng_float(rng);
        float3 p = area_light_point(SCENE_ARGS, L, (float2)(u0, u1), &n, &rad);
        float sides = 1.0f;
        if (L->two_sided) {
            sides = 2.0f;
            if (rng_float(rng) < 0.5f) n = -n;
        }
        e->dir = sample_cosine_hemisphere(n, rng_float(rng), rng_float(rng));
        e->org = offset_origin(SCENE_ARGS, p, n);
        /* Le cos / (pick * (1/A) * (1/sides) * cos/pi) = Le A pi sides / pick, Le where the
         * photon starts (for a textured emitter, pick is by the texture's mean: Light.power) */
        e->flux = rad * (L->area * PI_F * sides / (pick * info->total_power));
        e->cos_light = fmax(dot(e->dir, n), 0.0f);
        if (HAS_EMISSION_SPREAD) /* cosine-distributed still: the flux carries the spread (scene.cl) */
            e->flux *= emission_spread_factor(materials[shading[L->prim].material].emission_spread, e->cos_light);
        e->direct_pdf_a = pick / L->area;
        e->emission_pdf_w = e->direct_pdf_a * e->cos_light * INV_PI_F / sides;
        e->delta = false;
    } else if (HAS_POINT_LIGHTS && L->type == LIGHT_POINT) {
        float z = 1.0f - 2.0f * rng_float(rng);
        float r = sqrt(fmax(0.0f, 1.0f - z * z));
        float2 c = unit_circle(rng_float(rng));
        e->org = load3g(L->position);
        e->dir = (float3)(r * c.x, r * c.y, z);
        e->flux = rad * (4.0f * PI_F / (pick * info->total_power)); /* I / (pick / 4pi) */
        e->direct_pdf_a = pick;
        e->emission_pdf_w = pick * 0.25f * INV_PI_F;
    } else if (HAS_SPOT_LIGHTS && L->type == LIGHT_SPOT) {
        float3 axis = load3g(L->direction);
        e->org = load3g(L->position);
        e->dir = sample_cone(axis, L->cos_outer, rng_float(rng), rng_float(rng));
        float solid_angle = 2.0f * PI_F * (1.0f - L->cos_outer);
        e->flux = rad * (spot_falloff(L, dot(e->dir, axis)) * solid_angle / (pick * info->total_power));
        e->direct_pdf_a = pick;
        e->emission_pdf_w = pick / solid_angle;
    } else if (HAS_ENV_LIGHT && L->type == LIGHT_ENVIRONMENT) {
        /* Towards the scene from direction w, through a disc of the bounding sphere's radius R
         * facing it: L(w) pi R^2 / (pick pdf(w)). */
        float pdf;
        float3 w = env_sample(L, textures, light_cdf, rng_float(rng), rng_float(rng), &pdf);
        if (!(pdf > 0.0f)) return;
        float3 t, b;
        make_frame(w, &t, &b);
        float r = sqrt(rng_float(rng)) * info->radius;
        float2 c = unit_circle(rng_float(rng));
        e->org = load3c(info->center) + w * (1.01f * info->radius) + t * (r * c.x) + b * (r * c.y);
        e->dir = -w;
        float area = PI_F * info->radius * info->radius;
        e->flux = env_radiance(L, textures, texels, w) * (area / (pdf * pick * info->total_power));
        e->direct_pdf_a = pick * pdf;
        e->emission_pdf_w = e->direct_pdf_a / area;
        e->delta = false;
        e->finite = false;
    } else if (HAS_DIRECTIONAL_LIGHTS) { /* a disc covering the scene's bounding sphere, outside it */
        float3 d = load3g(L->direction);
        float3 t, b;
        make_frame(d, &t, &b);
        float2 disc;
        float r = sqrt(rng_float(rng)) * info->radius;
        disc = r * unit_circle(rng_float(rng));
        e->org = load3c(info->center) - d * (1.01f * info->radius) + t * disc.x + b * disc.y;
        e->dir = d;
        float area = PI_F * info->radius * info->radius;
        e->flux = rad * (area / (pick * info->total_power)); /* E / (pick / area) */
        e->direct_pdf_a = pick;
        e->emission_pdf_w = pick / area;
        e->finite = false;
    }
}

/* Emits one photon: origin, direction and flux (units of total power). */
void emit_photon(SCENE_PARAMS, Rng* rng, float3* org, float3* dir, float3* flux) {
    LightEmission e;
    emit_light(SCENE_ARGS, rng, &e);
    *org = e.org;
    *dir = e.dir;
    *flux = e.flux;
}

/* The solid-angle density with which sample_light picks a point seen at squared distance d2
 * and cosine cos_y on an emissive triangle: pick (power / total power) times d2 / (cos_y A),
 * from the triangle's power per area (uniform_power_per_area, emitter_power_per_area). The path
 * tracer's MIS weights take both densities from here, so that they sum to 1 exactly. */
float area_light_pdf(SCENE_PARAMS, float power_per_area, float d2, float cos_y) {
    return power_per_area / info->total_power * d2 / cos_y;
}

/* One light sample for direct lighting at x (SmallVCM's Light::Illuminate): the direction wi to
 * the light, the distance to shadow-test, contrib = Le G / pdf without the cosine at x, and pdf_w,
 * the sample's solid-angle density times the pick probability (for the environment, the density
 * env_light_pdf gives a ray that escapes). Vertex connection and merging also take emission_pdf_w
 * and cos_light, as emit_light would give them for the same light point and direction (pick
 * included), and delta: no ray can hit this light, and pdf_w then only relates contrib to Le (it
 * is pick d^2 for a punctual light, pick for a directional one). */
typedef struct {
    float3 wi, contrib;
    float dist, pdf_w, emission_pdf_w, cos_light;
    bool delta;
    uint light; /* the light's index (set by sample_chosen_light) */
} LightSample;

/* Whether sampling light l takes a point (two uniforms) besides its pick. */
bool light_takes_point(SCENE_PARAMS, uint l) {
    uint type = lights[l].type;
    if (HAS_AREA_LIGHTS && type == LIGHT_TRIANGLE) return true;
    return HAS_ENV_LIGHT && type == LIGHT_ENVIRONMENT;
}

/* Light l sampled from x with the uniforms u (used by area lights and the environment). Returns
 * false when the sample contributes nothing. */
bool sample_chosen_light(SCENE_PARAMS, float3 x, uint l, float2 u, LightSample* s) {
    s->pdf_w = s->emission_pdf_w = 0.0f;
    s->cos_light = 1.0f;
    s->delta = true;
    s->light = l;
    __global const Light* L = &lights[l];
    float pick = light_pick_pdf(SCENE_ARGS, l);
    float3 rad = load3g(L->radiance);
    float disc_area = PI_F * info->radius * info->radius;
    if (HAS_AREA_LIGHTS && L->type == LIGHT_TRIANGLE) {
        float3 ny;
        float3 y = area_light_point(SCENE_ARGS, L, u, &ny, &rad);
        float3 d = y - x;
        float d2 = dot(d, d);
        if (!(d2 > 0.0f)) return false;
        float len = sqrt(d2);
        s->wi = d / len;
        float cos_y = -dot(s->wi, ny); /* > 0: x sees the front face */
        if (L->two_sided) cos_y = fabs(cos_y);
        if (cos_y <= 0.0f) return false;
        if (HAS_EMISSION_SPREAD)
            rad *= emission_spread_factor(materials[shading[L->prim].material].emission_spread, cos_y);
        /* Le cos_y / d^2 / (pick / A): area sampling (Veach 1997, Eq. 8.10) */
        s->contrib = rad * (cos_y * L->area / (d2 * pick));
        bool textured = HAS_TEXTURES && materials[shading[L->prim].material].emissive_tex >= 0;
        float power_per_area =
            textured ? L->power / L->area : uniform_power_per_area(load3g(L->radiance), L->two_sided != 0u);
        s->pdf_w = area_light_pdf(SCENE_ARGS, power_per_area, d2, cos_y);
        s->cos_light = cos_y;
        s->emission_pdf_w = power_per_area / info->total_power * cos_y * INV_PI_F / (L->two_sided ? 2.0f : 1.0f);
        s->delta = false;
        /* Stop the shadow ray short of the light's own surface. */
        float m = fmax(fabs(y.x), fmax(fabs(y.y), fabs(y.z)));
        s->dist = len - 2.0f * (info->ray_eps + 4e-6f * m);
        return s->dist > 0.0f;
    }
    if (HAS_ENV_LIGHT && L->type == LIGHT_ENVIRONMENT) {
        float pdf;
        s->wi = env_sample(L, textures, light_cdf, u.x, u.y, &pdf);
        if (!(pdf > 0.0f)) return false;
        s->dist = 4.0f * info->radius + length(x - load3c(info->center));
        s->contrib = env_radiance(L, textures, texels, s->wi) / (pick * pdf);
        s->pdf_w = pick * pdf;
        s->emission_pdf_w = s->pdf_w / disc_area;
        s->delta = false;
        return max3(s->contrib) > 0.0f;
    }
    if (HAS_DIRECTIONAL_LIGHTS && L->type == LIGHT_DIRECTIONAL) {
        s->wi = -load3g(L->direction);
        s->dist = 4.0f * info->radius + length(x - load3c(info->center));
        s->contrib = rad / pick;
        s->pdf_w = pick;
        s->emission_pdf_w = pick / disc_area;
        return true;
    }
    if (!(HAS_POINT_LIGHTS || HAS_SPOT_LIGHTS)) return false;
    float3 d = load3g(L->position) - x;
    float d2 = dot(d, d);
    if (!(d2 > 0.0f)) return false;
    float len = sqrt(d2);
    s->wi = d / len;
    float falloff = 1.0f;
    if (HAS_SPOT_LIGHTS && L->type == LIGHT_SPOT) falloff = spot_falloff(L, -dot(s->wi, load3g(L->direction)));
    if (falloff <= 0.0f) return false;
    s->dist = len;
    s->contrib = rad * (falloff / (d2 * pick)); /* I / d^2 */
    s->pdf_w = pick * d2;
    s->emission_pdf_w = pick * (HAS_SPOT_LIGHTS && L->type == LIGHT_SPOT ? 1.0f / (2.0f * PI_F * (1.0f - L->cos_outer))
                                                                         : 0.25f * INV_PI_F);
    return true;
}

/* A light picked by u_pick in proportion to power, sampled with u. */
bool sample_light_u(SCENE_PARAMS, float3 x, float u_pick, float2 u, LightSample* s) {
    s->pdf_w = s->emission_pdf_w = 0.0f;
    s->cos_light = 1.0f;
    s->delta = true;
    if (info->num_lights == 0) return false;
    return sample_chosen_light(SCENE_ARGS, x, pick_light(SCENE_ARGS, u_pick), u, s);
}

/* A light picked by u->x in proportion to power among the lights below share of the CDF, and
 * u->x rescaled into the light's own range of it for the light's point (pbrt-v4's SampleDiscrete
 * reuse): the 2-D pair (a stratified or low-discrepancy point) then stays well spread over all the
 * lights together, where picking with a number of its own leaves each light's points stratified
 * apart. A light picked with probability under LIGHT_REUSE_MIN keeps too few of u->x's bits in its
 * range: it takes u_spare instead (uniform and independent of u->y given the light, so either way
 * the point is uniform and the estimate unbiased). */
#define LIGHT_REUSE_MIN (1.0f / 4096.0f)
uint pick_light_reuse(SCENE_PARAMS, float share, float2* u, float u_spare) {
    float v = u->x * share;
    if (!(v < share)) v = nextafter(share, 0.0f);
    uint l = pick_light(SCENE_ARGS, v);
    float c0 = light_cdf[l], w = light_cdf[l + 1u] - c0;
    u->x = w >= LIGHT_REUSE_MIN * share ? fmin((v - c0) / w, 0.99999994f) : u_spare;
    return l;
}

/* A light and its sample from one 2-D point u (pick_light_reuse). */
bool sample_light_reuse(SCENE_PARAMS, float3 x, float share, float2 u, float u_spare, LightSample* s) {
    s->pdf_w = s->emission_pdf_w = 0.0f;
    s->cos_light = 1.0f;
    s->delta = true;
    if (info->num_lights == 0) return false;
    uint l = pick_light_reuse(SCENE_ARGS, share, &u, u_spare);
    return sample_chosen_light(SCENE_ARGS, x, l, u, s);
}

/* The same from a random stream, which gives up the point's two numbers only to lights that take
 * them. */
bool sample_light_full(SCENE_PARAMS, float3 x, Rng* rng, LightSample* s) {
    s->pdf_w = s->emission_pdf_w = 0.0f;
    s->cos_light = 1.0f;
    s->delta = true;
    if (info->num_lights == 0) return false;
    uint l = pick_light(SCENE_ARGS, rng_float(rng));
    float2 u = (float2)(0.0f);
    if (light_takes_point(SCENE_ARGS, l)) {
        u.x = rng_float(rng);
        u.y = rng_float(rng);
    }
    return sample_chosen_light(SCENE_ARGS, x, l, u, s);
}

/* What next-event estimation uses of a sample: pdf_out is 0 for lights no ray can hit. */
void light_sample_out(const LightSample* s, float3* wi, float* dist, float3* contrib, float* pdf_out) {
    *wi = s->wi;
    *dist = s->dist;
    *contrib = s->contrib;
    *pdf_out = s->delta ? 0.0f : s->pdf_w;
}

/* sample_light_full for the path tracer and the eye pass. */
bool sample_light(SCENE_PARAMS, float3 x, Rng* rng, float3* wi, float* dist, float3* contrib, float* pdf_out) {
    LightSample s;
    bool ok = sample_light_full(SCENE_ARGS, x, rng, &s);
    light_sample_out(&s, wi, dist, contrib, pdf_out);
    return ok;
}

/* The density with which sample_light draws direction w towards the environment (MIS weights of
 * rays that escape). */
float env_light_pdf(SCENE_PARAMS, float3 w) {
    __global const Light* L = &lights[info->env_light];
    return light_pick_pdf(SCENE_ARGS, info->env_light) * env_pdf(L, textures, light_cdf, w);
}

#endif
