// Texture lookups on the host, as glTF samplers define them and kernels/scene.cl texture_lookup
// implements them: bilinear between texel centres at ((i + 0.5) / width, (j + 0.5) / height),
// REPEAT or CLAMP_TO_EDGE per axis, texels linear RGBA (already decoded from sRGB). In double
// precision: the reference the device is tested against, and what the emitters' power is
// integrated with.
#pragma once
#include <array>
#include <vector>

#include "scene/scene.h"

namespace clppm {

// Linear RGB of texture `index` at (u, v); any finite or non-finite coordinate is safe.
std::array<double, 3> sample_texture(const Scene& scene, int index, double u, double v);

} // namespace clppm
