// The guarded pre-scan of a glTF's raw JSON, before tinygltf touches memory or the file system:
// nesting depth, required extensions, URIs and image buffer views, the checks tinygltf does not
// make; and the GLB container's JSON chunk.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// Throws (ctx.fail) on anything tinygltf would mishandle; base is the scene's directory.
void prescan_json(const char* text, size_t size, const std::string& base, const LoadContext& ctx);

bool is_glb(const std::vector<unsigned char>& bytes);
// The JSON chunk of a GLB container, checked against the file's length (BIN chunk too).
std::pair<const char*, size_t> glb_json_chunk(const std::vector<unsigned char>& bytes, const LoadContext& ctx);

} // namespace clppm::gltf
