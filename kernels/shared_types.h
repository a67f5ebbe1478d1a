/* shared_types.h: the one definition of every struct that crosses the host/device boundary.
 *
 * Included by OpenCL C kernels and by C++ host code (inside namespace clppm::dev). Scalar fields
 * only: float3/float4 differ in size and alignment between host and device, so vectors are
 * spelled as float arrays. Host-side static_asserts in src/device/shared_types_check.cpp pin every
 * size and offset. */
#ifndef CLPPM_SHARED_TYPES_H
#define CLPPM_SHARED_TYPES_H

#ifdef __OPENCL_VERSION__
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
/* No fused multiply-add contraction: a specialised program and the generic one, or two work-group
 * sizes, must round alike (images are reproducible bit for bit). */
#pragma OPENCL FP_CONTRACT OFF
#include "kernel_features.h"
typedef uint u32;
typedef int i32;
typedef ulong u64;
typedef long i64;
#else
#include <cstdint>
namespace clppm {
namespace dev {
typedef uint32_t u32;
typedef int32_t i32;
typedef uint64_t u64;
typedef int64_t i64;
#endif

/* ---- geometry ------------------------------------------------------------------------------ */

/* Per-triangle shading attributes, indexed by triangle id (BVH leaf order). */
typedef struct {
    float n0[3], n1[3], n2[3]; /* shading normals at the three vertices (unit, world space) */
    float uv0[2], uv1[2], uv2[2];
    u32 material;
} TriShading; /* 64 bytes */

/* BVH node: see kernels/bvh_traverse.cl for the traversal and src/scene/bvh_build.cpp for the build.
 * A BVH_WIDTH-wide node: child bounds stored as SoA so one node test is BVH_WIDTH slab tests in
 * one vector operation per plane. 8 (one AVX float8 per plane on PoCL's CPU device) visits a
 * third fewer nodes than 4 and traced incoherent rays 15-20% faster in bench/traversal_bench;
 * 4 still works (change it here, the one definition host and kernels share). */
#define BVH_WIDTH 8
typedef struct {
    float bmin_x[BVH_WIDTH], bmin_y[BVH_WIDTH], bmin_z[BVH_WIDTH];
    float bmax_x[BVH_WIDTH], bmax_y[BVH_WIDTH], bmax_z[BVH_WIDTH];
    /* child[i] >= 0: inner node index; child[i] < 0: leaf of count[i] triangles, ~child[i] its
     * first triangle as built (build_bvh) and its first BvhTriBlock on the device
     * (bvh_leaf_blocks); count[i] == 0 and child[i] == -1 (i.e. ~0): empty slot. */
    i32 child[BVH_WIDTH];
    u32 count[BVH_WIDTH];
} BvhNode; /* 32 * BVH_WIDTH bytes */

/* A leaf's triangles for traversal, BVH_TRI_BLOCK at a time (a leaf of n triangles owns
 * ceil(n / BVH_TRI_BLOCK) consecutive blocks): vertex coordinates as SoA so one watertight test
 * covers the block in vector lanes, stored as the mesh has them (shared vertices bitwise equal).
 * A leaf's last block repeats its last triangle in unused lanes. Row 3 j + k of the block as
 * BVH_TRI_BLOCK-wide rows is coordinate k of vertex j; prim: triangle ids (leaf order).
 * 8, not 4: one float8 test per leaf of up to 8 triangles, so the SAH makes fewer, fuller leaves
 * (bench/RESULTS.md, "Closer to the hardware": 7.5 triangles a block, 10-15% more rays per second
 * than blocks of 4 on PoCL). The kernel also takes 4. */
#define BVH_TRI_BLOCK 8
typedef struct {
    float v[9][BVH_TRI_BLOCK];
    u32 prim[BVH_TRI_BLOCK];
} BvhTriBlock; /* 40 * BVH_TRI_BLOCK bytes */

/* The builder guarantees at most this many inner nodes on any root-to-leaf path (root = 1), so a
 * traversal stack of (BVH_WIDTH - 1) * BVH_MAX_DEPTH + 1 entries cannot overflow: each level
 * pushes at most BVH_WIDTH - 1 siblings. */
#define BVH_MAX_DEPTH 24

/* ---- materials and textures ---------------------------------------------------------------- */

#define MATERIAL_FLAG_DOUBLE_SIDED 1u
/* transmission through a thin wall (no KHR_materials_volume, or thicknessFactor 0): no refraction */
#define MATERIAL_FLAG_THIN_WALLED 2u
/* KHR_materials_unlit: the base colour shown as it is; the surface scatters nothing (scene.cl) */
#define MATERIAL_FLAG_UNLIT 4u
/* KHR_materials_volume with thicknessFactor > 0 on a transmitting material: the closed mesh holds a
 * volume of its own, so the world's medium (kernels/medium.cl) stops at its surface */
#define MATERIAL_FLAG_ENCLOSES_VOLUME 8u
/* Its closed volume holds a light (src/scene/volume_nesting.h): paths sample lights from its medium. */
#define MATERIAL_FLAG_HOLDS_LIGHTS 16u

/* glTF alphaMode */
#define ALPHA_OPAQUE 0u
#define ALPHA_MASK 1u
#define ALPHA_BLEND 2u

/* glTF 2.0 metallic-roughness material (Appendix B) with KHR_materials_ior, _specular,
 * _transmission and _emissive_strength; kernels/bsdf.cl is its scattering model. */
typedef struct {
    float base_color[4];     /* linear RGB; [3] alpha (unused) */
    float emission[3];       /* emitted radiance, emissiveFactor * emissive_strength */
    u32 outside;             /* the closed volume the mesh lies in (src/scene/volume_nesting.h): 0 the
                              * world's, k + 1 material k's (kernels/medium.cl) */
    float specular_color[4]; /* KHR_materials_specular: specularColorFactor, [3] specularFactor */
    float metallic, roughness, transmission, ior;
    i32 base_color_tex;         /* index into Texture array (sRGB decoded), -1 when none */
    u32 flags;                  /* MATERIAL_FLAG_* */
    i32 metallic_roughness_tex; /* linear texture: G scales roughness, B metallic; -1 when none */
    i32 emissive_tex;           /* sRGB texture times emission; -1 when none */
    i32 normal_tex;             /* linear tangent-space normal map; -1 when none */
    float normal_scale;         /* normalTexture.scale: multiplies the map's x and y */
    float alpha_cutoff;         /* alphaCutoff, for ALPHA_MASK */
    u32 alpha_mode;             /* ALPHA_OPAQUE, ALPHA_MASK or ALPHA_BLEND (kernels/alpha.cl) */
    float attenuation[4];       /* KHR_materials_volume: absorption coefficient per unit length (RGB) */
    i32 transmission_tex;       /* transmissionTexture (linear, R scales transmission); -1 when none */
    i32 specular_tex;           /* KHR_materials_specular specularTexture (linear, A); -1 when none */
    i32 specular_color_tex;     /* specularColorTexture (sRGB, RGB); -1 when none */
    float emission_spread;      /* tan of half an area light's spread (kernels/scene.cl); 0: Lambertian */
    /* KHR_materials_clearcoat (kernels/bsdf.cl): a GGX coat of ior 1.5 over the rest */
    float clearcoat;              /* clearcoatFactor */
    float clearcoat_roughness;    /* clearcoatRoughnessFactor */
    i32 clearcoat_tex;            /* clearcoatTexture (linear, R scales the factor); -1 when none */
    i32 clearcoat_roughness_tex;  /* clearcoatRoughnessTexture (linear, G); -1 when none */
    i32 clearcoat_normal_tex;     /* clearcoatNormalTexture; -1: the coat follows the smooth normal */
    float clearcoat_normal_scale; /* its scale */
    /* KHR_materials_sheen (kernels/bsdf.cl): a Charlie lobe over the base */
    float sheen_color[3];    /* sheenColorFactor (linear RGB); 0: no sheen */
    float sheen_roughness;   /* sheenRoughnessFactor */
    i32 sheen_color_tex;     /* sheenColorTexture (sRGB, RGB); -1 when none */
    i32 sheen_roughness_tex; /* sheenRoughnessTexture (linear, A); -1 when none */
    /* KHR_materials_iridescence (kernels/iridescence.cl): a thin film on the specular layer and metal */
    float iridescence;              /* iridescenceFactor; 0: none */
    float iridescence_ior;          /* iridescenceIor */
    float iridescence_thickness[2]; /* iridescenceThicknessMinimum, -Maximum (nm) */
    i32 iridescence_tex;            /* iridescenceTexture (linear, R); -1 when none */
    i32 iridescence_thickness_tex;  /* iridescenceThicknessTexture (linear, G); -1: the maximum */
    /* KHR_materials_anisotropy (kernels/bsdf.cl): GGX stretched along a direction in the tangent plane */
    float anisotropy_strength; /* anisotropyStrength; 0: isotropic */
    float anisotropy_rotation; /* anisotropyRotation (radians, from the tangent towards the bitangent) */
    i32 anisotropy_tex;        /* anisotropyTexture (linear: RG direction, B strength); -1 when none */
    /* KHR_materials_diffuse_transmission (kernels/bsdf.cl): part of the diffuse lobe turned to the other side */
    float diffuse_transmission;          /* diffuseTransmissionFactor; 0: none */
    i32 diffuse_transmission_tex;        /* diffuseTransmissionTexture (linear, A); -1 when none */
    i32 diffuse_transmission_color_tex;  /* diffuseTransmissionColorTexture (sRGB, RGB); -1 when none */
    float diffuse_transmission_color[3]; /* diffuseTransmissionColorFactor (linear RGB) */
    /* KHR_materials_dispersion (kernels/dispersion.cl): 20 / Abbe number; 0: none */
    float dispersion;
    /* KHR_materials_volume_scatter (kernels/medium.cl): inside a mesh that encloses a volume, the
     * attenuation above is the extinction sigma_t of a medium that scatters this single-scattering
     * albedo of it (RGB, from multiscatterColor); [3] the Henyey-Greenstein g (scatterAnisotropy).
     * All 0: the volume only absorbs. */
    float scatter[4];
} Material; /* 256 bytes */

/* Sampler bits of a texture. Wrap per axis (glTF sampler wrapS, wrapT): clamp s, clamp t, mirror
 * s, mirror t; none set is REPEAT. TEXTURE_NEAREST: magFilter NEAREST, the texel the coordinate
 * falls in; without it, bilinear between texel centres. */
#define TEXTURE_CLAMP_S 1u
#define TEXTURE_CLAMP_T 2u
#define TEXTURE_MIRROR_S 4u
#define TEXTURE_MIRROR_T 8u
#define TEXTURE_NEAREST 16u

/* path_trace's screen_log2 argument for each pixel's own Sobol' sequence (kernels/sobol.cl
 * sobol_make); any other value is L of the screen-space layout (sobol_make_screen). */
#define SOBOL_PER_PIXEL 0xFFFFFFFFu

/* One texture reference: an image's texels, its sampler's wrap modes, the texture coordinate
 * set and KHR_texture_transform's affine map of it (identity without the extension). */
typedef struct {
    u32 offset; /* first texel in the texel buffer (float4 linear RGBA) */
    u32 width, height;
    u32 wrap;       /* TEXTURE_* bits: wrap modes and filter */
    float xform[6]; /* u' = x0 u + x1 v + x2, v' = x3 u + x4 v + x5 */
    u32 texcoord;   /* 0: TEXCOORD_0, 1: TEXCOORD_1 */
    u32 pad0;
} Texture; /* 48 bytes */

/* ---- lights -------------------------------------------------------------------------------- */

#define LIGHT_TRIANGLE 0u    /* an emissive triangle: radiance = material emission */
#define LIGHT_POINT 1u       /* KHR_lights_punctual point: intensity in W/sr */
#define LIGHT_SPOT 2u        /* KHR_lights_punctual spot */
#define LIGHT_DIRECTIONAL 3u /* KHR_lights_punctual directional: irradiance in W/m^2 */
#define LIGHT_ENVIRONMENT                                                                                              \
    4u                          /* radiance from every direction (--env, --env-color, the default light):
                              * kernels/environment.cl */
#define ENV_UNIFORM 0xffffffffu /* LIGHT_ENVIRONMENT.prim without a map */

typedef struct {
    u32 type;
    u32 prim;      /* LIGHT_TRIANGLE: triangle id */
    u32 two_sided; /* LIGHT_TRIANGLE: emits from both faces */
    float power;   /* scalar power (mean over RGB), W: drives photon emission probability */
    float position[4];
    float direction[4]; /* spot, directional: unit direction the light travels */
    float radiance[4];  /* triangle: Le (times the emissive texture, when any); point/spot:
                         * intensity I; directional: irradiance E; environment: the factor on
                         * its map (or its uniform radiance) */
    /* LIGHT_ENVIRONMENT: prim is the map's texture (ENV_UNIFORM: none), two_sided the offset of
     * its sampling distribution in light_cdf, position (cos, sin) of its turn about +Y and
     * position[2] 1 when camera rays do not see it (--env-hidden). */
    float cos_inner, cos_outer, area, pad0;
} Light; /* 80 bytes */

/* ---- camera and scene constants ------------------------------------------------------------ */

typedef struct {
    float origin[4];  /* [3]: znear, the clip plane's distance along forward (0: none) */
    float forward[4]; /* unit view direction; [3]: 1 for an orthographic camera */
    float right[4];   /* right * tan(xfov/2): screen x in [-1,1] maps onto it (orthographic: * xmag) */
    float up[4];      /* up * tan(yfov/2) (orthographic: * ymag) */
    u32 width, height;
    float lens_radius;    /* 0: pinhole */
    float focus_distance; /* along forward */
} Camera;                 /* 80 bytes */

typedef struct {
    float center[4];   /* bounding sphere of the scene */
    float radius;      /* bounding sphere radius */
    float ray_eps;     /* origin offset along the normal, relative to the scene size */
    float total_power; /* sum of Light.power: every photon leaves a light carrying this (RGB-scaled) */
    u32 num_lights;
    u32 num_tris;
    u32 num_emissive_tris;
    u32 max_bounces;   /* eye and photon path depth limit */
    u32 vertex_colors; /* 1: the colors buffer holds COLOR_0 for every triangle; 0: it is empty */
    u32 texcoord1;     /* 1: the uv1 buffer holds TEXCOORD_1 for every triangle; 0: it is empty */
    u32 env_light;     /* index of the LIGHT_ENVIRONMENT light; ENV_UNIFORM (~0) when there is none */
    u32 pad2, pad3;
    /* The world's homogeneous medium (kernels/medium.cl), filling space outside the closed volumes:
     * extinction sigma_t per scene unit (RGB), [3] 1 when there is a medium, 0 when there is none;
     * single-scattering albedo sigma_s / sigma_t (RGB), [3] the Henyey-Greenstein g. */
    float medium_sigma_t[4];
    float medium_albedo[4];
} SceneInfo; /* 96 bytes */

/* ---- progressive photon mapping -------------------------------------------------------------- */

/* A hit point from the eye pass (Hachisuka et al. 2008, Sec. 4.1): where the eye path first
 * meets a non-specular surface, with what the gather needs to evaluate the BRDF there.
 * Statistics (R, N, tau) live apart in HitStats.
 * A volume hit point, where the eye path scattered in a participating medium (kernels/medium.cl),
 * has alpha HITPOINT_VOLUME_ALPHA, the medium's sigma_t in color, its Henyey-Greenstein g in f90,
 * weight the throughput times sigma_s T / pdf of the free flight, and wo_oct; it gathers the
 * photons stored in media within a sphere (kernels/gather.cl).
 * A beam (alpha HITPOINT_BEAM_ALPHA; SPPM and PPPM in media, one per pixel after the pixels' hit
 * points) is a camera ray's segment through a medium, o + t d for t in [0, t_max]: pos o, f0 d,
 * dielectric t_max, color sigma_t, sheen the single-scattering albedo, f90 g, weight the throughput
 * at o, wo_oct -d; it gathers the photons stored in media within a cylinder around the segment
 * (kernels/beam.cl, the beam radiance estimate). */
typedef struct {
    float pos[3];
    u32 pixel;       /* y * width + x; HITPOINT_NONE marks an unused slot */
    float weight[3]; /* path throughput from the camera up to this surface */
    float footprint; /* pixel footprint at the hit, world units (initial radius heuristic) */
    /* The material there, as kernels/bsdf.cl's Bsdf holds it: the lobes the gather evaluates are
     * the diffuse one and, when alpha >= GLOSSY_HITPOINT_ALPHA, the specular and metal ones. */
    float color[3];       /* base colour */
    float alpha;          /* GGX alpha = roughness^2 */
    float f0[3];          /* the dielectric layer's Schlick F0 */
    float f90;            /* and its F90 (KHR_materials_specular specularFactor) */
    float dielectric;     /* weight of the dielectric base: (1 - metallic)(1 - transmission) */
    float metal;          /* weight of the conductor: metallic */
    u32 normal_oct;       /* shading normal on the side the eye path arrives from, octahedral 2x16 */
    u32 ng_oct;           /* geometric normal, same side (shadow-ray offsets) */
    u32 wo_oct;           /* unit direction back along the eye path */
    u32 nl_oct;           /* smooth normal (before any normal map), same side */
    float coat;           /* KHR_materials_clearcoat: the coat's weight (0: none) */
    float coat_alpha;     /* its GGX alpha */
    u32 nc_oct;           /* its normal, same side */
    float sheen[3];       /* KHR_materials_sheen: the sheen colour (0: none) */
    float sheen_r;        /* and roughness */
    float irid;           /* KHR_materials_iridescence: the film's weight (0: none) */
    float irid_ior;       /* its index */
    float irid_d;         /* its thickness (nm) */
    u32 t_oct;            /* KHR_materials_anisotropy: the direction of alpha_t, octahedral */
    float alpha_t;        /* GGX alpha along it (= alpha when isotropic) */
    float translucent[3]; /* KHR_materials_diffuse_transmission: its colour times its weight (0: none) */
    float dt;             /* and that weight, which the diffuse reflection loses */
    /* The closed volumes on the surface's two sides (kernels/medium.cl; 0 the world's, k + 1
     * material k's): the one the eye path arrived through, and the one behind the surface, which
     * light samples through a translucent surface cross. Media only (0 elsewhere). */
    u32 volume, volume_behind;
} HitPoint; /* 160 bytes */

#define HITPOINT_NONE 0xffffffffu
#define HITPOINT_VOLUME_ALPHA (-1.0f)
#define HITPOINT_BEAM_ALPHA (-2.0f)

/* What one pass's gather found for one hit point: M and the sum of photon flux, in fixed point
 * (FLUX_FIXED_SCALE) so that the sum does not depend on the order photons are visited in. */
typedef struct {
    i64 flux[3];
    u32 m;
    u32 pad0;
} PassFlux; /* 32 bytes */

/* Per hit point statistics of Sec. 4.2, in double: N beyond 2^24 and tau over millions of
 * passes keep their precision (float would stop counting at N = 2^24). */
typedef struct {
    double r2;        /* R(x)^2 */
    double n;         /* N(x): accumulated (alpha-discounted) photon count */
    double tau[3];    /* unnormalised flux, in units of SceneInfo.total_power */
    double direct[3]; /* explicit direct lighting: running sum over passes */
} HitStats;           /* 64 bytes */

/* A photon hit on a non-specular surface, or (PHOTON_VOLUME_FLAG) a collision in a participating
 * medium: there flux is what arrived times sigma_t T / pdf of the free flight (kernels/medium.cl),
 * about the arriving flux itself, so sums stay in range at any density and scene scale, and
 * normal_oct is unused. */
typedef struct {
    float pos[3];
    u32 normal_oct; /* surface normal, octahedral 2x16 bits */
    float flux[3];  /* in units of SceneInfo.total_power */
    u32 wi_oct;     /* unit direction towards where the photon came from, octahedral 2x16 */
} Photon;           /* 32 bytes */

/* The sign bit of Photon.flux[1] marks a photon stored in a medium (flux[0]'s marks dispersion). */
#define PHOTON_VOLUME_FLAG 0x80000000u

/* The uniform hashed grid over this pass's photons (Sec. 4.3). */
typedef struct {
    float origin[4]; /* bounds minimum */
    float inv_cell;  /* 1 / cell size */
    u32 table_size;  /* power of two */
    u32 num_photons;
    u32 pad0;
} GridInfo; /* 32 bytes */

/* Visual importance for photons (Hachisuka and Jensen 2009, "Robust adaptive photon tracing using
 * photon path visibility"): one Markov chain of photon paths per photon index of a pass, whose
 * target is the path's visibility V(u) in primary sample space. The state is its first
 * PHOTON_CHAIN_DIMS numbers, and the seed of the stream that continues them (kernels/
 * photon_chain.cl). step > 0 once the chain has a visible state; 0 before. */
#define PHOTON_CHAIN_DIMS 12
#define PHOTON_CHAIN_STEPS 32 /* steps of each chain per pass: one uniform path each */
#define PHOTON_CHAIN_CACHE 8  /* photons of a state kept to deposit it again without tracing it */
#define PHOTON_CHAIN_UNCACHED 0xffffffffu
typedef struct {
    float u[PHOTON_CHAIN_DIMS]; /* the state's first numbers, each in [0, 1) */
    u32 tail[2];                /* the seed of the numbers after them */
    float step;                 /* the mutation's size, adapted towards an acceptance of 0.234 */
    u32 mutations;              /* mutations proposed since the chain found its first state */
    u32 cached;                 /* the state's photons in the cache, or PHOTON_CHAIN_UNCACHED */
    u32 pad[3];
} PhotonChain; /* 80 bytes */

/* What a batch's chains did, summed by atomics (PhotonChains, src/integrators/photon_chains.h). */
#define CHAIN_UNIFORM_VISIBLE 0 /* uniform paths that were visible (V_c of Sec. 4.2) */
#define CHAIN_STATES 1          /* chains that deposited a state's photons */
#define CHAIN_ACCEPTED 2        /* mutations accepted */
#define CHAIN_MUTATIONS 3       /* mutations proposed */
#define CHAIN_COUNTS 4

/* Vertex connection and merging (kernels/vcm.cl): a light sub-path's vertex on a surface with a
 * non-delta lobe. The grid and the gather read pos, normal_oct and wi_oct as a photon's; the
 * connections rebuild the surface from (prim, u, v) and the arrival direction. */
typedef struct {
    float pos[3];
    u32 normal_oct;          /* shading normal on the side the light arrived from */
    float throughput[3];     /* in units of SceneInfo.total_power, as photon flux */
    u32 wi_oct;              /* unit direction back towards the previous vertex */
    float d_vcm, d_vc, d_vm; /* the partial MIS sums (kernels/vcm_mis.h) */
    u32 prim;
    float u, v;      /* barycentrics on prim */
    u32 prev;        /* the same sub-path's previous stored vertex; VCM_NO_VERTEX at its first */
    u32 path_length; /* segments from the light */
} LightVertex;       /* 64 bytes */

#define VCM_NO_VERTEX 0xffffffffu

/* What both sub-path kernels of a VCM pass are told (vcm_light, vcm_camera in kernels/vcm.cl), passed
 * by value; the host fills it once a pass (src/integrators/vcm_integrator.cpp). */
typedef struct {
    u64 seed, pass;    /* the render's seed and this pass (from 1): the random streams */
    double light_unit; /* camera side: a light-side sum's unit in radiance, total power over area_scale */
    double vm_norm;    /* camera side: area_scale / (pi r^2 N_L), the merging estimate's normalisation */
    double splat_unit; /* camera side: light_unit / splat_scale, one fixed-point unit of a splat */
    float light_paths; /* N_L: light sub-paths in a pass (one per pixel) */
    float vm_factor;   /* eta^2 of the MIS sums (Georgiev et al. 2012), 0 without merging */
    float vc_factor;   /* 1 / eta^2 when connecting and merging both (VCM), else 0 */
    float area_scale;  /* the scene's unit of area: densities per scene-relative area */
    float r2;          /* camera side: the merging radius squared */
    float splat_scale; /* light side: fixed-point scale of the light tracer's splats */
    u32 mode;          /* VCM_MODE_* (kernels/vcm_mis.h) */
    u32 max_len;       /* the longest path, in segments */
} VcmPass;             /* 72 bytes */

/* Fixed point used for per-pass flux sums: exact, so the sum is the same in any order. */
#define FLUX_FIXED_SCALE 4294967296.0 /* 2^32 */

/* ---- launch constants: the host sizes buffers and launches by these ------------------------ */

#define PPM_EYE_SLOTS 4  /* hit points one PPM eye sample may store (it splits at glass and metal) */
#define SPPM_EYE_SLOTS 1 /* SPPM and PPPM: one visible point per pixel and pass */
#define PPM_UPDATE_WG 64 /* ppm_update's work-group size (kernels/ppm_update.cl) */
#define GRID_SCAN_WG 256 /* grid_scan's one work-group (kernels/hash_grid.cl) */

/* Per-pixel statistics of the progressive error estimate (Hachisuka, Jarosz and Jensen 2010;
 * kernels/error_estimate.cl), kept only when error estimation is on. Running means (Welford) over
 * the passes j = 1..n of the single-pass luminance estimates L_j and of the single-pass bias
 * estimates B_j = R_j^2 Lap_j L / 8: the image is exactly the mean of the L_j (tau_i / R_i^2 =
 * sum_j tau_M,j / R_j^2), so their spread is its noise and mean_j B_j its bias. */
typedef struct {
    double n;         /* passes accumulated */
    double mean_l;    /* mean of L_j (luminance) */
    double m2_l;      /* sum of squared deviations of L_j from their mean (Welford) */
    double mean_bias; /* mean of B_j */
    double m2_bias;   /* sum of squared deviations of B_j from their mean: the bias estimate's own noise */
    double
        direct_y; /* luminance of the pixel's HitStats.direct after the previous pass: this pass's share is the difference */
} ErrorStats; /* 48 bytes */

#ifndef __OPENCL_VERSION__
} // namespace dev
} // namespace clppm
#endif

#endif
