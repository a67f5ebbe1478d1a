/* bsdf_types.cl: the Bsdf that surface_bsdf resolves a material into and every lobe reads, its
 * lobe bits, the sample bsdf_sample returns, and which of glTF's extensions a Bsdf carries (each
 * test folds to false where the scene's kernels were built without the feature). kernels/bsdf.cl
 * is the interface and describes the model. */
#ifndef CLPPM_BSDF_TYPES_CL
#define CLPPM_BSDF_TYPES_CL

#include "kernel_features.h"
#include "sampling.cl"

/* Reflection lobes at least this rough (GGX alpha = roughness^2) get hit points and are gathered
 * with the BSDF; smoother ones are sampled through by the eye pass, where a density estimate
 * would blur the reflection. */
#define GLOSSY_HITPOINT_ALPHA 0.04f
/* GGX alpha below this is a mirror: the lobe is a delta (roughness below 0.01). */
#define MIRROR_ALPHA 1e-4f

#define LOBE_DIFFUSE 1u
#define LOBE_SPECULAR 2u
#define LOBE_GLASS 4u
#define LOBE_METAL 8u
#define LOBE_COAT 16u
#define LOBE_SHEEN 32u
#define LOBE_ALL 63u
/* The coat's Schlick F0: ior 1.5, as KHR_materials_clearcoat fixes it. */
#define COAT_F0 0.04f

/* What a path carries (pbrt-v4's TransportMode; Veach 1997, Sec. 5.2): a camera path radiance, a
 * light path (a photon, a light sub-path) importance. The BSDF below is written for importance;
 * refraction into a medium of relative index eta compresses radiance by eta^2, so a camera path's
 * refracted light is 1/eta^2 of that. Paths that leave a solid as they entered it see both
 * factors cancel, so only a camera vertex inside a refracting solid (VCM merging and connecting at
 * rough glass) tells the two apart. */
#define TRANSPORT_RADIANCE 0u
#define TRANSPORT_IMPORTANCE 1u

typedef struct {
    float3 ns, ng;                  /* shading and geometric normal on the side of wo */
    float3 nl;                      /* the smooth normal, ns before any normal map (bsdf_smooth_side) */
    float3 base;                    /* base colour */
    float3 f0;                      /* dielectric layer: Schlick F0 */
    float f90;                      /* and F90 */
    float alpha;                    /* GGX alpha of both reflection lobes */
    float dielectric, glass, metal; /* lobe weights */
    float eta;                      /* LOBE_GLASS: relative index n_t / n_i for light crossing from the ns side */
    bool thin;                      /* LOBE_GLASS: thin-walled, transmission does not bend */
    bool radiance;                  /* carries radiance (TRANSPORT_RADIANCE): refraction scales by 1/eta^2 */
    bool front;                     /* the side of ns is outside the mesh (the winding's front) */
    float3 sigma;                   /* KHR_materials_volume: the mesh's absorption coefficient */
    float3 nc;                      /* LOBE_COAT: the coat's normal, on the side of wo */
    float coat, coat_alpha;         /* LOBE_COAT: weight (0: none) and GGX alpha */
    float3 sheen;                   /* LOBE_SHEEN: colour (0: none) */
    float sheen_r;                  /* LOBE_SHEEN: roughness, at least SHEEN_MIN_ROUGHNESS */
    float irid, irid_ior, irid_d;   /* KHR_materials_iridescence: weight (0: none), index, thickness (nm) */
    float3 ta;                      /* KHR_materials_anisotropy: the direction of alpha_t, across ns */
    float alpha_t;                  /* GGX alpha along ta; alpha (across) otherwise */
    float3 translucent;             /* KHR_materials_diffuse_transmission: dt times its colour (0: none) */
    float dt;                       /* and dt, the part of the diffuse lobe turned to the other side */
} Bsdf;

typedef struct {
    float3 wi;
    float3 weight; /* f cos / pdf; for a delta lobe its coefficient over the probability of choosing it */
    float pdf;     /* solid-angle density of wi over the sampled lobe set; 0 for a delta lobe */
    bool delta;
    bool below; /* wi leaves through the surface (refraction) */
} BsdfSample;

/* KHR_materials_anisotropy: the GGX lobes (layer, metal, glass) stretch to alpha_t along ta. */
bool has_aniso(const Bsdf* b) { return HAS_ANISOTROPY && b->alpha_t != b->alpha; }

/* A mirror only when smooth in every direction. */
bool bsdf_is_mirror(const Bsdf* b) { return (HAS_ANISOTROPY ? fmax(b->alpha, b->alpha_t) : b->alpha) < MIRROR_ALPHA; }

/* The dielectric base's specular layer (KHR_materials_specular can turn it off). */
bool has_layer(const Bsdf* b) { return HAS_SPECULAR_LAYER && b->dielectric > 0.0f && b->f90 > 0.0f; }

/* KHR_materials_diffuse_transmission: part of the diffuse lobe reaches the other side. */
bool has_translucent(const Bsdf* b) { return HAS_DIFFUSE_TRANSMISSION && b->dt > 0.0f; }

bool has_coat(const Bsdf* b) { return HAS_CLEARCOAT && b->coat > 0.0f; }

bool coat_is_mirror(const Bsdf* b) { return b->coat_alpha < MIRROR_ALPHA; }

bool has_sheen(const Bsdf* b) { return HAS_SHEEN && max3(b->sheen) > 0.0f; }

bool has_irid(const Bsdf* b) { return HAS_IRIDESCENCE && b->irid > 0.0f; }

#endif
