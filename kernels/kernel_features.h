/* kernel_features.h: what the program is built for. The host passes -DHAS_X=0 for every feature the
 * scene does not use (src/scene/scene_features.cpp), so that, for example, a diffuse scene under
 * one area light never pays for glass, textures or spot lights, in registers or in branches. Each
 * flag defaults to 1: without options the program is the generic one that renders any scene.
 *
 * CLPPM_KERNEL_FEATURES is the one list of features: X(flag, field, description). The host makes
 * its SceneFeatures fields, build options and description from it; the kernels below give each
 * flag its default (the preprocessor cannot generate #ifndef blocks, so they are written out once,
 * and the enum after them fails to compile if the list names a flag without a default). */
#ifndef CLPPM_FEATURES_H
#define CLPPM_FEATURES_H

#define CLPPM_KERNEL_FEATURES(X)                                                                                       \
    X(HAS_SPECULAR_LAYER, specular_layer, "specular layer")                                                            \
    X(HAS_METAL, metal, "metal")                                                                                       \
    X(HAS_GLASS, glass, "glass")                                                                                       \
    X(HAS_ROUGH_GLASS, rough_glass, "rough glass")                                                                     \
    X(HAS_TEXTURES, textures, "textures")                                                                              \
    X(HAS_NORMAL_MAPS, normal_maps, "normal maps")                                                                     \
    X(HAS_VERTEX_COLORS, vertex_colors, "vertex colours")                                                              \
    X(HAS_ALPHA, alpha, "alpha mask or blend")                                                                         \
    X(HAS_VOLUME, volume, "absorbing volumes")                                                                         \
    X(HAS_AREA_LIGHTS, area_lights, "area lights")                                                                     \
    X(HAS_POINT_LIGHTS, point_lights, "point lights")                                                                  \
    X(HAS_SPOT_LIGHTS, spot_lights, "spot lights")                                                                     \
    X(HAS_DIRECTIONAL_LIGHTS, directional_lights, "directional lights")                                                \
    X(HAS_ENV_LIGHT, env_light, "environment light")                                                                   \
    X(HAS_THIN_LENS, thin_lens, "thin lens")                                                                           \
    X(HAS_EMISSION_SPREAD, emission_spread, "emission spread")                                                         \
    X(HAS_UNLIT, unlit, "unlit materials")                                                                             \
    X(HAS_CLEARCOAT, clearcoat, "clearcoat")                                                                           \
    X(HAS_SHEEN, sheen, "sheen")                                                                                       \
    X(HAS_ORTHOGRAPHIC, orthographic, "orthographic camera")                                                           \
    X(HAS_IRIDESCENCE, iridescence, "iridescence")                                                                     \
    X(HAS_ANISOTROPY, anisotropy, "anisotropy")                                                                        \
    X(HAS_DIFFUSE_TRANSMISSION, diffuse_transmission, "diffuse transmission")                                          \
    X(HAS_DISPERSION, dispersion, "dispersion")                                                                        \
    X(HAS_MEDIUM, medium, "participating media")

#ifdef __OPENCL_VERSION__

#ifndef HAS_SPECULAR_LAYER
#define HAS_SPECULAR_LAYER 1
#endif
#ifndef HAS_METAL
#define HAS_METAL 1
#endif
#ifndef HAS_GLASS
#define HAS_GLASS 1
#endif
#ifndef HAS_ROUGH_GLASS
#define HAS_ROUGH_GLASS 1
#endif
#ifndef HAS_TEXTURES
#define HAS_TEXTURES 1
#endif
#ifndef HAS_NORMAL_MAPS
#define HAS_NORMAL_MAPS 1
#endif
#ifndef HAS_VERTEX_COLORS
#define HAS_VERTEX_COLORS 1
#endif
#ifndef HAS_ALPHA
#define HAS_ALPHA 1
#endif
#ifndef HAS_VOLUME
#define HAS_VOLUME 1
#endif
#ifndef HAS_AREA_LIGHTS
#define HAS_AREA_LIGHTS 1
#endif
#ifndef HAS_POINT_LIGHTS
#define HAS_POINT_LIGHTS 1
#endif
#ifndef HAS_SPOT_LIGHTS
#define HAS_SPOT_LIGHTS 1
#endif
#ifndef HAS_DIRECTIONAL_LIGHTS
#define HAS_DIRECTIONAL_LIGHTS 1
#endif
#ifndef HAS_ENV_LIGHT
#define HAS_ENV_LIGHT 1
#endif
#ifndef HAS_EMISSION_SPREAD
#define HAS_EMISSION_SPREAD 1
#endif
#ifndef HAS_DISPERSION
#define HAS_DISPERSION 1
#endif
#ifndef HAS_MEDIUM
#define HAS_MEDIUM 1
#endif
#ifndef HAS_DIFFUSE_TRANSMISSION
#define HAS_DIFFUSE_TRANSMISSION 1
#endif
#ifndef HAS_ANISOTROPY
#define HAS_ANISOTROPY 1
#endif
#ifndef HAS_IRIDESCENCE
#define HAS_IRIDESCENCE 1
#endif
#ifndef HAS_ORTHOGRAPHIC
#define HAS_ORTHOGRAPHIC 1
#endif
#ifndef HAS_SHEEN
#define HAS_SHEEN 1
#endif
#ifndef HAS_CLEARCOAT
#define HAS_CLEARCOAT 1
#endif
#ifndef HAS_UNLIT
#define HAS_UNLIT 1
#endif
#ifndef HAS_THIN_LENS
#define HAS_THIN_LENS 1
#endif

/* Every flag of the list has a default above: a missing one is an undeclared identifier here. */
#define CLPPM_FEATURE_TERM(flag, field, text) +flag
enum { CLPPM_FEATURES_WITH_DEFAULTS = 0 CLPPM_KERNEL_FEATURES(CLPPM_FEATURE_TERM) };
#undef CLPPM_FEATURE_TERM

/* Any surface that is not Lambertian. */
#define HAS_NON_DIFFUSE                                                                                                \
    (HAS_SPECULAR_LAYER || HAS_METAL || HAS_GLASS || HAS_CLEARCOAT || HAS_SHEEN || HAS_DIFFUSE_TRANSMISSION)

#endif /* __OPENCL_VERSION__ */

#endif
