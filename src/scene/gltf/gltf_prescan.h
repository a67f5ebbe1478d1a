// The guarded pre-scan of a glTF's raw JSON, before tinygltf touches memory or the file system:
// nesting depth, required extensions, URIs and image buffer views, the checks tinygltf does not
// make; and the GLB container's JSON chunk.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/gltf/gltf_context.h"

namespace clppm::gltf {

// Throws (ctx.fail) on anything tinygltf would mishandle; base is the scene's directory. Returns
// the parsed document.
nlohmann::json prescan_json(const char* text, size_t size, const std::string& base, const LoadContext& ctx);

// tinygltf 2.7 refuses a primitive's indices accessor without a bufferView, which is how
// KHR_draco_mesh_compression files declare theirs (the indices are in the Draco data). Removes
// `indices` from such primitives (the Draco decoder supplies them); true when it changed root.
bool drop_draco_indices(nlohmann::json& root);

// The GLB container `bytes` with its JSON chunk replaced by `text` (padded with spaces to 4
// bytes, as the container requires) and every later chunk kept.
std::vector<unsigned char> glb_with_json(const std::vector<unsigned char>& bytes, const std::string& text);

bool is_glb(const std::vector<unsigned char>& bytes);
// The JSON chunk of a GLB container, checked against the file's length (BIN chunk too).
std::pair<const char*, size_t> glb_json_chunk(const std::vector<unsigned char>& bytes, const LoadContext& ctx);

} // namespace clppm::gltf
