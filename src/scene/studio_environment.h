// The built-in studio environment (--env studio): a neutral procedural sky for looking at a
// model, as model-viewer's neutral lighting is, where the uniform white world shows shapes flat.
// A soft gradient from a darker ground to a brighter sky, a broad key light from the upper front
// left (seen from a camera on +Z looking down -Z), a weaker rim light from the upper back right.
// Scaled so that a surface facing up receives irradiance pi, as under the uniform white world of
// radiance 1: a white Lambertian floor shows radiance 1 under either.
#pragma once
#include "io/image_io.h"

namespace clppm {

// The studio as an equirectangular map of width x height texels (docs/scenes.md's convention: top row
// +Y, centre -Z, u towards +X), each texel the mean over its area of the radiance below.
Image studio_environment(int width = 256, int height = 128);

// The studio's radiance (before scaling) towards unit direction (x, y, z); for the test.
double studio_radiance_unscaled(double x, double y, double z, int channel);

} // namespace clppm
