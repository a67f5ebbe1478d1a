// The emitted power of a punctual light (mean over RGB, watts as clppm reads glTF's units): how
// often it emits photons and is picked for direct light. The one formula, used by the loader to
// refuse lights too bright for a float and by the device scene to weight the lights.
#pragma once
#include <cstddef>

#include "scene/scene.h"
#include "shared_types.h"

namespace clppm {

// Mean over triangle `tri` (and over RGB) of its material's emission times its emissive
// texture: the integral of the texture's bilinear interpolant by the centroid rule on n^2 equal
// sub-triangles, n about twice the triangle's longest edge in texels (at least 2, at most 64),
// so every texel the triangle covers is sampled. It sets how often the triangle emits photons
// and is picked for direct light (its power is mean A pi per side); photons and light samples
// then carry the texture's value where they start, so the estimate's error costs variance, never
// bias.
double textured_emission_mean(const Scene& scene, size_t tri);

// Point: 4 pi I. Spot: the glTF falloff (a squared linear ramp in cos between the cones)
// integrated over the cone, 2 pi I ((1 - cos_inner) + (cos_inner - cos_outer) / 3).
// Directional: E over the disc of the scene's bounding sphere, pi r^2 E (0 while the scene's
// radius is unknown).
double punctual_light_power(const dev::Light& light, double scene_radius);

} // namespace clppm
