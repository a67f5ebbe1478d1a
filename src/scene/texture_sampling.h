// Texture lookups on the host, as glTF samplers define them and kernels/scene.cl texture_lookup
// implements them: bilinear between texel centres at ((i + 0.5) / width, (j + 0.5) / height), or
// with TEXTURE_NEAREST (magFilter NEAREST) the texel (floor(u width), floor(v height)); REPEAT,
// MIRRORED_REPEAT or CLAMP_TO_EDGE per axis, texels linear RGBA (already decoded from sRGB). In double
// precision: the reference the device is tested against, and what the emitters' power is
// integrated with.
#pragma once
#include <array>
#include <vector>

#include "scene/scene.h"

namespace clppm {

// Linear RGB of texture `index` at (u, v) of its own coordinate set (Texture.texcoord), before
// its KHR_texture_transform, which is applied here; any finite or non-finite value is safe.
std::array<double, 3> sample_texture(const Scene& scene, int index, double u, double v);

// A texture reference with the identity transform on TEXCOORD_0.
dev::Texture plain_texture(uint32_t offset, uint32_t width, uint32_t height, uint32_t wrap);

} // namespace clppm
