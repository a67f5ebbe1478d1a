// Host-side proof that shared_types.h lays out every struct the same way the OpenCL C compiler
// does: explicit sizes and offsets, scalar fields only (STYLE.md, "Host and kernels share one truth").
#include <cstddef>

#include "shared_types.h"

namespace clppm::dev {

#define CLPPM_CHECK_SIZE(T, n) static_assert(sizeof(T) == (n), #T " size differs from the kernel's")
#define CLPPM_CHECK_OFFSET(T, f, n) static_assert(offsetof(T, f) == (n), #T "." #f " offset differs")

CLPPM_CHECK_SIZE(TriShading, 64);
CLPPM_CHECK_OFFSET(TriShading, uv0, 36);
CLPPM_CHECK_OFFSET(TriShading, material, 60);

CLPPM_CHECK_SIZE(BvhNode, 32 * BVH_WIDTH);
CLPPM_CHECK_OFFSET(BvhNode, bmax_x, 12 * BVH_WIDTH);
CLPPM_CHECK_OFFSET(BvhNode, child, 24 * BVH_WIDTH);
CLPPM_CHECK_OFFSET(BvhNode, count, 28 * BVH_WIDTH);
CLPPM_CHECK_SIZE(BvhTriBlock, 40 * BVH_TRI_BLOCK);
CLPPM_CHECK_OFFSET(BvhTriBlock, prim, 36 * BVH_TRI_BLOCK);
static_assert(BVH_WIDTH == 4 || BVH_WIDTH == 8, "bvh_traverse.cl has float4 and float8 node tests");

CLPPM_CHECK_SIZE(Material, 256);
CLPPM_CHECK_OFFSET(Material, outside, 28);
CLPPM_CHECK_OFFSET(Material, scatter, 240);
CLPPM_CHECK_OFFSET(Material, diffuse_transmission, 212);
CLPPM_CHECK_OFFSET(Material, diffuse_transmission_color, 224);
CLPPM_CHECK_OFFSET(Material, dispersion, 236);
CLPPM_CHECK_OFFSET(Material, anisotropy_strength, 200);
CLPPM_CHECK_OFFSET(Material, anisotropy_tex, 208);
CLPPM_CHECK_OFFSET(Material, iridescence, 176);
CLPPM_CHECK_OFFSET(Material, iridescence_thickness_tex, 196);
CLPPM_CHECK_OFFSET(Material, sheen_color, 152);
CLPPM_CHECK_OFFSET(Material, sheen_roughness_tex, 172);
CLPPM_CHECK_OFFSET(Material, emission_spread, 124);
CLPPM_CHECK_OFFSET(Material, clearcoat, 128);
CLPPM_CHECK_OFFSET(Material, clearcoat_normal_scale, 148);
CLPPM_CHECK_OFFSET(Material, emission, 16);
CLPPM_CHECK_OFFSET(Material, specular_color, 32);
CLPPM_CHECK_OFFSET(Material, metallic, 48);
CLPPM_CHECK_OFFSET(Material, base_color_tex, 64);
CLPPM_CHECK_OFFSET(Material, flags, 68);
CLPPM_CHECK_OFFSET(Material, metallic_roughness_tex, 72);
CLPPM_CHECK_OFFSET(Material, emissive_tex, 76);
CLPPM_CHECK_OFFSET(Material, normal_tex, 80);
CLPPM_CHECK_OFFSET(Material, normal_scale, 84);
CLPPM_CHECK_OFFSET(Material, alpha_mode, 92);
CLPPM_CHECK_OFFSET(Material, attenuation, 96);
CLPPM_CHECK_OFFSET(Material, transmission_tex, 112);
CLPPM_CHECK_OFFSET(Material, specular_color_tex, 120);

CLPPM_CHECK_SIZE(Texture, 48);
CLPPM_CHECK_OFFSET(Texture, xform, 16);
CLPPM_CHECK_OFFSET(Texture, texcoord, 40);

CLPPM_CHECK_SIZE(Light, 80);
CLPPM_CHECK_OFFSET(Light, power, 12);
CLPPM_CHECK_OFFSET(Light, position, 16);
CLPPM_CHECK_OFFSET(Light, radiance, 48);
CLPPM_CHECK_OFFSET(Light, cos_inner, 64);

CLPPM_CHECK_SIZE(Camera, 80);
CLPPM_CHECK_OFFSET(Camera, width, 64);
CLPPM_CHECK_OFFSET(Camera, focus_distance, 76);

CLPPM_CHECK_SIZE(SceneInfo, 96);
CLPPM_CHECK_OFFSET(SceneInfo, medium_sigma_t, 64);
CLPPM_CHECK_OFFSET(SceneInfo, medium_albedo, 80);
CLPPM_CHECK_OFFSET(SceneInfo, radius, 16);
CLPPM_CHECK_OFFSET(SceneInfo, num_lights, 28);
CLPPM_CHECK_OFFSET(SceneInfo, max_bounces, 40);
CLPPM_CHECK_OFFSET(SceneInfo, vertex_colors, 44);
CLPPM_CHECK_OFFSET(SceneInfo, texcoord1, 48);

CLPPM_CHECK_SIZE(HitPoint, 160);
CLPPM_CHECK_OFFSET(HitPoint, translucent, 136);
CLPPM_CHECK_OFFSET(HitPoint, dt, 148);
CLPPM_CHECK_OFFSET(HitPoint, volume_behind, 156);
CLPPM_CHECK_OFFSET(HitPoint, t_oct, 128);
CLPPM_CHECK_OFFSET(HitPoint, irid, 116);
CLPPM_CHECK_OFFSET(HitPoint, sheen, 100);
CLPPM_CHECK_OFFSET(HitPoint, coat, 88);
CLPPM_CHECK_OFFSET(HitPoint, nc_oct, 96);
CLPPM_CHECK_OFFSET(HitPoint, pixel, 12);
CLPPM_CHECK_OFFSET(HitPoint, weight, 16);
CLPPM_CHECK_OFFSET(HitPoint, footprint, 28);
CLPPM_CHECK_OFFSET(HitPoint, color, 32);
CLPPM_CHECK_OFFSET(HitPoint, alpha, 44);
CLPPM_CHECK_OFFSET(HitPoint, f0, 48);
CLPPM_CHECK_OFFSET(HitPoint, f90, 60);
CLPPM_CHECK_OFFSET(HitPoint, dielectric, 64);
CLPPM_CHECK_OFFSET(HitPoint, metal, 68);
CLPPM_CHECK_OFFSET(HitPoint, normal_oct, 72);
CLPPM_CHECK_OFFSET(HitPoint, wo_oct, 80);
CLPPM_CHECK_OFFSET(HitPoint, nl_oct, 84);

CLPPM_CHECK_SIZE(HitStats, 64);
CLPPM_CHECK_OFFSET(HitStats, n, 8);
CLPPM_CHECK_OFFSET(HitStats, tau, 16);
CLPPM_CHECK_OFFSET(HitStats, direct, 40);

CLPPM_CHECK_SIZE(PassFlux, 32);
CLPPM_CHECK_OFFSET(PassFlux, m, 24);

CLPPM_CHECK_SIZE(Photon, 32);
CLPPM_CHECK_OFFSET(Photon, normal_oct, 12);
CLPPM_CHECK_OFFSET(Photon, flux, 16);
CLPPM_CHECK_OFFSET(Photon, wi_oct, 28);

CLPPM_CHECK_SIZE(LightVertex, 64);
CLPPM_CHECK_OFFSET(LightVertex, normal_oct, 12);
CLPPM_CHECK_OFFSET(LightVertex, throughput, 16);
CLPPM_CHECK_OFFSET(LightVertex, wi_oct, 28);
CLPPM_CHECK_OFFSET(LightVertex, d_vcm, 32);
CLPPM_CHECK_OFFSET(LightVertex, prim, 44);
CLPPM_CHECK_OFFSET(LightVertex, prev, 56);
CLPPM_CHECK_OFFSET(LightVertex, path_length, 60);

CLPPM_CHECK_SIZE(VcmPass, 72);
CLPPM_CHECK_OFFSET(VcmPass, pass, 8);
CLPPM_CHECK_OFFSET(VcmPass, light_unit, 16);
CLPPM_CHECK_OFFSET(VcmPass, splat_unit, 32);
CLPPM_CHECK_OFFSET(VcmPass, light_paths, 40);
CLPPM_CHECK_OFFSET(VcmPass, r2, 56);
CLPPM_CHECK_OFFSET(VcmPass, splat_scale, 60);
CLPPM_CHECK_OFFSET(VcmPass, mode, 64);
CLPPM_CHECK_OFFSET(VcmPass, max_len, 68);

CLPPM_CHECK_SIZE(GridInfo, 32);
CLPPM_CHECK_OFFSET(GridInfo, inv_cell, 16);
CLPPM_CHECK_SIZE(PhotonChain, 80);
CLPPM_CHECK_OFFSET(PhotonChain, cached, 64);
CLPPM_CHECK_OFFSET(PhotonChain, tail, 48);
CLPPM_CHECK_OFFSET(PhotonChain, step, 56);

CLPPM_CHECK_SIZE(ErrorStats, 48);
CLPPM_CHECK_OFFSET(ErrorStats, mean_l, 8);
CLPPM_CHECK_OFFSET(ErrorStats, mean_bias, 24);
CLPPM_CHECK_OFFSET(ErrorStats, m2_bias, 32);
CLPPM_CHECK_OFFSET(ErrorStats, direct_y, 40);
static_assert(alignof(ErrorStats) == 8, "ErrorStats holds doubles only");

} // namespace clppm::dev
