// What every stage of glTF loading shares: the limits that turn hostile input into an error, the
// extensions clppm reads, the LoadContext that fails with one line naming the file and collects
// warnings, and the helpers that keep tinygltf's and nlohmann's messages on one line.
#pragma once
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "scene/scene.h"
#include "util/error.h"
#include "util/narrow_to_float.h"

namespace clppm::gltf {

// Limits that turn hostile or broken input into an error instead of a huge allocation or a hang.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;     // any one file read
constexpr uint64_t kMaxExternalBytes = uint64_t(1) << 31; // all external files together
constexpr uint64_t kMaxAccessorCount = uint64_t(1) << 31;
constexpr size_t kMaxTriangles = size_t(1) << 25;  // ~3.3 GB of host triangle data
constexpr size_t kMaxNodeVisits = size_t(1) << 20; // shared subtrees instanced many times
constexpr size_t kMaxTexels = size_t(1) << 26;     // 1 GiB of float4 texels, all images
constexpr int kMaxImageSide = 16384;
constexpr int kMaxJsonDepth = 64;      // tinygltf converts extras recursively
constexpr size_t kMaxByteStride = 252; // glTF 2.0 limit
// Sparse accessors (and ones without a bufferView) are expanded to dense copies: a few bytes of
// JSON can ask for 2^31 elements, so all such copies together are capped.
constexpr uint64_t kMaxExpandedAccessorBytes = uint64_t(1) << 30;
constexpr double kPi = 3.14159265358979323846;

// Each is read as its specification says (docs/scenes.md).
inline const std::set<std::string> kSupportedExtensions = {"KHR_lights_punctual",
                                                           "KHR_materials_emissive_strength",
                                                           "KHR_materials_transmission",
                                                           "KHR_materials_ior",
                                                           "KHR_materials_specular",
                                                           "KHR_mesh_quantization",
                                                           "EXT_mesh_gpu_instancing",
                                                           "KHR_draco_mesh_compression",
                                                           "EXT_texture_webp",
                                                           "KHR_texture_transform",
                                                           "KHR_materials_volume",
                                                           "KHR_materials_dispersion",
                                                           "KHR_materials_variants",
                                                           "KHR_materials_unlit",
                                                           "KHR_materials_clearcoat",
                                                           "KHR_materials_sheen",
                                                           "KHR_materials_iridescence",
                                                           "KHR_materials_anisotropy",
                                                           "KHR_materials_pbrSpecularGlossiness",
                                                           "KHR_materials_diffuse_transmission",
                                                           "KHR_materials_volume_scatter"};

// The default scene's (else the first scene's) extras entry `key`; nullptr where there is none.
const tinygltf::Value* scene_extra(const tinygltf::Model& model, const char* key);

// Error messages are one line: tinygltf and nlohmann texts are joined with "; ".
std::string one_line(const std::string& text);
// tinygltf quotes whole data URIs in its errors: keep messages readable.
std::string clipped(const std::string& text, size_t max_chars = 300);
// The non-empty lines of text, each made one line.
std::vector<std::string> split_lines(const std::string& text);
// Text from the file (a name, a URI) as it may appear in a one-line message: control characters
// escaped ("\n", "\x01").
std::string printable(const std::string& text);

class LoadContext {
public:
    LoadContext(std::string source, Scene* scene) : source_(std::move(source)), scene_(scene) {}
    const std::string& source() const { return source_; }

    // Messages are one line whatever the file holds: control characters are escaped.
    [[noreturn]] void fail(const std::string& what) const { throw Error(source_ + ": " + printable(what)); }

    // Each distinct warning once: instanced meshes would otherwise repeat theirs.
    void warn(const std::string& what) {
        if (seen_.insert(what).second) scene_->warnings.push_back(printable(what));
    }

private:
    std::string source_;
    Scene* scene_;
    std::set<std::string> seen_;
};

inline std::string labelled(const char* kind, int index, const std::string& name) {
    std::string s = std::string(kind) + " " + std::to_string(index);
    return name.empty() ? s : s + " ('" + clipped(printable(name), 80) + "')";
}

} // namespace clppm::gltf
