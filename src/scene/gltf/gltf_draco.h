// KHR_draco_mesh_compression: every compressed primitive is decoded with Debian's libdraco into
// a buffer of its own, and its indices and compressed attributes are pointed at fresh accessors
// into that buffer, so the rest of the loader reads it like any uncompressed primitive.
#pragma once
#include <tiny_gltf.h>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// Decodes in place; a primitive whose data does not decode, or whose extension names a missing
// bufferView or attribute, is an error naming it.
void decode_draco_primitives(tinygltf::Model& m, LoadContext& ctx);

} // namespace clppm::gltf
