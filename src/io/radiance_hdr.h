// Radiance RGBE (.hdr) images (Greg Ward's format: a text header ending in an empty line, the
// resolution "-Y H +X W", then H scanlines, flat or run-length encoded per channel), read with
// every byte accounted for. stb_image's reader, which clppm used before, fills a truncated file's
// missing pixels with black without a word, and loops for ever on some truncated run-length
// scanlines: a half-written environment map must be an error instead.
#pragma once
#include <string>

#include "io/image_io.h"

namespace clppm {

// Linear RGB, top row first, each texel m 2^(e - 136) as stb_image and Radiance decode it. Throws
// Error with the reason alone ("truncated: ...", "not a Radiance HDR file", ...): the caller names
// the file and the option.
Image read_radiance_hdr(const std::string& path);

} // namespace clppm
