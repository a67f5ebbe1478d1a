/* surface_bsdf.cl: a glTF material at a surface resolved into the Bsdf of kernels/bsdf.cl
 * (factors times textures), and KHR_materials_volume's absorption along a segment from it. */
#ifndef CLPPM_SURFACE_BSDF_CL
#define CLPPM_SURFACE_BSDF_CL

#include "scene.cl"
#include "bsdf_types.cl"

/* The glTF material at this surface (factors times textures), for a path that carries `transport`
 * (TRANSPORT_RADIANCE from the camera, TRANSPORT_IMPORTANCE from a light). */
Bsdf surface_bsdf(SCENE_PARAMS, const Surface* s, uint transport) {
    __global const Material* m = &materials[s->material];
    Bsdf b;
    b.radiance = transport == TRANSPORT_RADIANCE;
    b.ns = s->ns;
    b.ng = s->ng;
    b.nl = s->nl;
    b.base = surface_base_color(SCENE_ARGS, s);
    float metallic = HAS_METAL ? m->metallic : 0.0f;
    float r = m->roughness;
    if (HAS_TEXTURES && m->metallic_roughness_tex >= 0) { /* glTF: G is roughness, B metallic */
        float3 mr = texture_lookup(SCENE_ARGS, m->metallic_roughness_tex, s->uv);
        r *= mr.y;
        metallic *= mr.z;
    }
    float t = HAS_GLASS ? m->transmission : 0.0f;
    if (HAS_GLASS && HAS_TEXTURES && m->transmission_tex >= 0)
        t *= texture_lookup(SCENE_ARGS, m->transmission_tex, s->uv).x;
    b.metal = metallic;
    b.glass = (1.0f - metallic) * t;
    b.dielectric = (1.0f - metallic) * (1.0f - t);
    b.alpha = r * r;
    /* KHR_materials_ior and KHR_materials_specular: F0 = ((ior - 1) / (ior + 1))^2 times the
     * specular colour, at most 1, both F0 and F90 times the specular factor. */
    float q = (m->ior - 1.0f) / (m->ior + 1.0f);
    float spec = HAS_SPECULAR_LAYER ? m->specular_color[3] : 0.0f;
    float3 spec_color = load3g(m->specular_color);
    if (HAS_SPECULAR_LAYER && HAS_TEXTURES && m->specular_tex >= 0)
        spec *= texture_rgba(textures, texels, m->specular_tex, s->uv).w;
    if (HAS_SPECULAR_LAYER && HAS_TEXTURES && m->specular_color_tex >= 0)
        spec_color *= texture_lookup(SCENE_ARGS, m->specular_color_tex, s->uv);
    b.f0 = fmin(q * q * spec_color, (float3)(1.0f)) * spec;
    b.f90 = spec;
    b.thin = (m->flags & MATERIAL_FLAG_THIN_WALLED) != 0u;
    b.eta = s->front || b.thin ? m->ior : 1.0f / m->ior;
    b.front = s->front;
    b.sigma = HAS_VOLUME ? load3g(m->attenuation) : (float3)(0.0f);
    b.nc = s->nc;
    b.coat = HAS_CLEARCOAT ? m->clearcoat : 0.0f;
    b.coat_alpha = 0.0f;
    if (HAS_CLEARCOAT && b.coat > 0.0f) { /* clearcoatTexture's R, clearcoatRoughnessTexture's G */
        float cr = m->clearcoat_roughness;
        if (HAS_TEXTURES && m->clearcoat_tex >= 0) b.coat *= texture_lookup(SCENE_ARGS, m->clearcoat_tex, s->uv).x;
        if (HAS_TEXTURES && m->clearcoat_roughness_tex >= 0)
            cr *= texture_lookup(SCENE_ARGS, m->clearcoat_roughness_tex, s->uv).y;
        b.coat_alpha = cr * cr;
    }
    b.sheen = HAS_SHEEN ? load3g(m->sheen_color) : (float3)(0.0f);
    b.sheen_r = 1.0f;
    if (HAS_SHEEN && max3(b.sheen) > 0.0f) { /* sheenColorTexture's RGB, sheenRoughnessTexture's A */
        float sr = m->sheen_roughness;
        if (HAS_TEXTURES && m->sheen_color_tex >= 0) b.sheen *= texture_lookup(SCENE_ARGS, m->sheen_color_tex, s->uv);
        if (HAS_TEXTURES && m->sheen_roughness_tex >= 0)
            sr *= texture_rgba(textures, texels, m->sheen_roughness_tex, s->uv).w;
        b.sheen_r = fmax(sr, SHEEN_MIN_ROUGHNESS);
    }
    b.ta = s->ta;
    b.alpha_t = b.alpha;
    if (HAS_ANISOTROPY && m->anisotropy_strength > 0.0f) { /* anisotropyTexture's B scales the strength */
        float st = m->anisotropy_strength;
        if (HAS_TEXTURES && m->anisotropy_tex >= 0) st *= texture_rgba(textures, texels, m->anisotropy_tex, s->uv).z;
        if (st > 0.0f) {
            b.alpha = fmax(b.alpha, 1e-3f); /* a lobe of no width across would be singular */
            b.alpha_t = b.alpha + (1.0f - b.alpha) * st * st;
        }
    }
    b.irid = HAS_IRIDESCENCE ? m->iridescence : 0.0f;
    b.irid_ior = m->iridescence_ior;
    b.irid_d = m->iridescence_thickness[1];
    if (HAS_IRIDESCENCE && b.irid > 0.0f) { /* iridescenceTexture's R, iridescenceThicknessTexture's G */
        if (HAS_TEXTURES && m->iridescence_tex >= 0) b.irid *= texture_lookup(SCENE_ARGS, m->iridescence_tex, s->uv).x;
        if (HAS_TEXTURES && m->iridescence_thickness_tex >= 0) {
            float g = texture_lookup(SCENE_ARGS, m->iridescence_thickness_tex, s->uv).y;
            b.irid_d = m->iridescence_thickness[0] + (m->iridescence_thickness[1] - m->iridescence_thickness[0]) * g;
        }
    }
    b.dt = HAS_DIFFUSE_TRANSMISSION ? m->diffuse_transmission : 0.0f;
    b.translucent = (float3)(0.0f);
    if (HAS_DIFFUSE_TRANSMISSION && b.dt > 0.0f) { /* diffuseTransmissionTexture's A, the colour texture's RGB */
        if (HAS_TEXTURES && m->diffuse_transmission_tex >= 0)
            b.dt *= texture_rgba(textures, texels, m->diffuse_transmission_tex, s->uv).w;
        b.translucent = load3g(m->diffuse_transmission_color) * b.dt;
        if (HAS_TEXTURES && m->diffuse_transmission_color_tex >= 0)
            b.translucent *= texture_lookup(SCENE_ARGS, m->diffuse_transmission_color_tex, s->uv);
    }
    if (surface_is_unlit(SCENE_ARGS, s)) {
        b.dt = 0.0f;
        b.dielectric = b.glass = b.metal = b.coat = 0.0f;
        b.sheen = (float3)(0.0f);
    }
    return b;
}

/* KHR_materials_volume on a straight segment of length dist that leaves the surface along w (a
 * light sample's shadow ray, a connection): Beer-Lambert's exp(-sigma dist) when the segment runs
 * inside the surface's mesh, that is when w enters it through the front face or stays on the
 * inside of a back face; 1 elsewhere. Paths that are traced get the same factor on arrival
 * (volume_transmittance). */
float3 bsdf_segment_transmittance(const Bsdf* b, float3 w, float dist) {
    if (!HAS_VOLUME || !(max3(b->sigma) > 0.0f)) return (float3)(1.0f);
    bool inside = b->front ? dot(w, b->ng) < 0.0f : dot(w, b->ng) > 0.0f;
    return inside ? exp(-b->sigma * dist) : (float3)(1.0f);
}

#endif
