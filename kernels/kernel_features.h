/* kernel_features.h: what the program is built for. The host passes -DHAS_X=0 for every feature the
 * scene does not use (src/scene_features.cpp), so that, for example, a diffuse scene under one
 * area light never pays for glass, textures or spot lights, in registers or in branches. Each flag
 * defaults to 1: without options the program is the generic one that renders any scene. */
#ifndef CLPPM_FEATURES_H
#define CLPPM_FEATURES_H

#ifndef HAS_MIRROR
#define HAS_MIRROR 1
#endif
#ifndef HAS_GLOSSY
#define HAS_GLOSSY 1
#endif
#ifndef HAS_DIELECTRIC
#define HAS_DIELECTRIC 1
#endif
#ifndef HAS_METAL_MIX
#define HAS_METAL_MIX 1
#endif
#ifndef HAS_TEXTURES
#define HAS_TEXTURES 1
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
#ifndef HAS_THIN_LENS
#define HAS_THIN_LENS 1
#endif

/* Any surface that is not Lambertian. */
#define HAS_NON_DIFFUSE (HAS_MIRROR || HAS_GLOSSY || HAS_DIELECTRIC || HAS_METAL_MIX)

#endif
