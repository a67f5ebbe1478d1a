// The live view's compact image (GET /image.f16, cli/live_view.h): linear RGB as IEEE binary16, so
// that the page applies exposure and tone curve itself (an exposure change costs no request) and
// the server does no PNG compression. Little-endian throughout:
//
//   bytes 0..3   "CLH1"
//   bytes 4..7   uint32 width
//   bytes 8..11  uint32 height
//   bytes 12..15 float32 base_ev: the stored values are linear radiance * 2^base_ev
//   then width * height * 3 binary16 values, R G B per pixel, row-major, top row first.
//
// base_ev is the exposure the PNG would apply (--exposure, plus the automatic one), so the stored
// values sit near display range whatever the light power; values above binary16's largest finite
// 65504 are stored as 65504 (white at any exposure the page offers, -8..8 EV), negative ones as 0,
// and a pixel with a NaN or infinite channel as NaN in all three (the PNG shows it magenta).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/image_io.h"

namespace clppm {

constexpr size_t kHalfImageHeaderBytes = 16;

std::string encode_half_image(const Image& img, double base_ev);

// The inverse, for tests and tools: the values as stored (times 2^base_ev). Throws clppm::Error
// on a truncated or foreign buffer.
struct HalfImage {
    uint32_t width = 0, height = 0;
    float base_ev = 0;
    std::vector<float> rgb;
};
HalfImage decode_half_image(const std::string& bytes);

} // namespace clppm
