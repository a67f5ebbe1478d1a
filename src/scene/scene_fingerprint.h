// A 64-bit fingerprint of everything in a scene that shapes the image: a checkpoint of another
// scene is refused on resume.
#pragma once
#include <cstdint>

#include "scene/scene.h"

namespace clppm {

uint64_t scene_fingerprint(const Scene& scene);

} // namespace clppm
