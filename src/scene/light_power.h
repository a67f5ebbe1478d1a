// The emitted power of a punctual light (mean over RGB, watts as clppm reads glTF's units): how
// often it emits photons and is picked for direct light. The one formula, used by the loader to
// refuse lights too bright for a float and by the device scene to weight the lights.
#pragma once
#include "shared_types.h"

namespace clppm {

// Point: 4 pi I. Spot: the glTF falloff (a squared linear ramp in cos between the cones)
// integrated over the cone, 2 pi I ((1 - cos_inner) + (cos_inner - cos_outer) / 3).
// Directional: E over the disc of the scene's bounding sphere, pi r^2 E (0 while the scene's
// radius is unknown).
double punctual_light_power(const dev::Light& light, double scene_radius);

} // namespace clppm
