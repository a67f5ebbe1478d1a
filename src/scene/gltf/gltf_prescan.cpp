#include "scene/gltf/gltf_prescan.h"

#include <algorithm>
#include <cstdint>

#include <filesystem>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene/gltf/gltf_files.h"

namespace clppm::gltf {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Deepest nesting of [] and {} outside strings. Checked before parsing because tinygltf converts
// extras recursively (stack depth), and nlohmann's callback parser is quadratic in array length.
int json_nesting_depth(const char* text, size_t size) {
    int depth = 0, deepest = 0;
    bool in_string = false;
    for (size_t i = 0; i < size; ++i) {
        char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return deepest;
}

json parse_json_guarded(const char* text, size_t size, const LoadContext& ctx) {
    if (json_nesting_depth(text, size) > kMaxJsonDepth)
        ctx.fail("malformed JSON: nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    try {
        return json::parse(text, text + size);
    } catch (const json::exception& e) {
        ctx.fail("malformed JSON: " + one_line(e.what()));
    }
}

const json& member_array(const json& root, const char* key) {
    static const json empty = json::array();
    auto it = root.find(key);
    return (it != root.end() && it->is_array()) ? *it : empty;
}

void check_required_extensions(const json& root, const LoadContext& ctx) {
    for (const json& name : member_array(root, "extensionsRequired")) {
        if (!name.is_string()) ctx.fail("extensionsRequired holds a non-string entry");
        if (!kSupportedExtensions.count(name.get<std::string>()))
            ctx.fail("required extension '" + name.get<std::string>() + "' is not supported");
    }
}

// The same decoding tinygltf applies before it opens a URI.
std::string url_decode(const std::string& uri) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && i + 2 < uri.size()) {
            out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

void check_uri(const std::string& uri, const std::string& owner, const std::string& base, const LoadContext& ctx) {
    if (tinygltf::IsDataURI(uri)) return;
    std::string path = url_decode(uri);
    std::string bad = owner + " URI '" + clipped(printable(uri), 200) + "'";
    if (base.empty()) ctx.fail(bad + " names an external file, but this scene has no directory");
    if (std::any_of(path.begin(), path.end(), [](char c) { return (unsigned char)c < 0x20; }))
        ctx.fail(bad + " contains control characters");
    if (path.find("://") != std::string::npos || path.rfind("file:", 0) == 0)
        ctx.fail(bad + " is not a relative file path");
    fs::path p = fs::path(path).lexically_normal();
    if (p.is_absolute() || path[0] == '/' || path[0] == '\\' || (!p.empty() && *p.begin() == ".."))
        ctx.fail(bad + " points outside the scene directory");
}

void check_uris(const json& root, const std::string& base, const LoadContext& ctx) {
    const char* sections[] = {"buffers", "images"};
    for (const char* section : sections) {
        const json& items = member_array(root, section);
        for (size_t i = 0; i < items.size(); ++i) {
            auto uri = items[i].is_object() ? items[i].find("uri") : items[i].end();
            if (items[i].is_object() && uri != items[i].end() && uri->is_string())
                check_uri(uri->get<std::string>(), std::string(section, strlen(section) - 1) + " " + std::to_string(i),
                          base, ctx);
        }
    }
}

uint64_t unsigned_member(const json& o, const char* key, uint64_t fallback) {
    auto it = o.find(key);
    return (it != o.end() && it->is_number_unsigned()) ? it->get<uint64_t>() : fallback;
}

// An index as tinygltf reads it: any JSON integer, cast to int (so 2^32 + 3 would read as 3).
// One outside int is refused, so that the pre-scan checks the element tinygltf will use; -1
// when absent or not an integer (tinygltf reports or ignores those).
int64_t index_member(const json& o, const char* key, const std::string& owner, const LoadContext& ctx) {
    auto it = o.find(key);
    if (it == o.end() || !it->is_number_integer()) return -1;
    bool fits = it->is_number_unsigned() ? it->get<uint64_t>() <= uint64_t(std::numeric_limits<int>::max())
                                         : it->get<int64_t>() >= std::numeric_limits<int>::min();
    if (!fits) ctx.fail(owner + " " + key + " " + it->dump() + " is not a valid index");
    return it->get<int64_t>();
}

// tinygltf hands an image's bufferView bytes to the decoder without a bounds check.
void check_image_buffer_views(const json& root, const LoadContext& ctx) {
    const json& views = member_array(root, "bufferViews");
    const json& buffers = member_array(root, "buffers");
    const json& images = member_array(root, "images");
    for (size_t i = 0; i < images.size(); ++i) {
        const json& image = images[i];
        if (!image.is_object() || !image.contains("bufferView")) continue;
        int64_t v = index_member(image, "bufferView", "image " + std::to_string(i), ctx);
        if (v < 0 || uint64_t(v) >= views.size() || !views[size_t(v)].is_object()) continue; // tinygltf reports it
        const json& view = views[size_t(v)];
        int64_t b = index_member(view, "buffer", "bufferView " + std::to_string(v), ctx);
        if (b < 0 || uint64_t(b) >= buffers.size() || !buffers[size_t(b)].is_object()) continue;
        uint64_t size = unsigned_member(buffers[size_t(b)], "byteLength", 0);
        uint64_t offset = unsigned_member(view, "byteOffset", 0);
        uint64_t length = unsigned_member(view, "byteLength", UINT64_MAX);
        if (offset > size || length > size - offset)
            ctx.fail("bufferView " + std::to_string(v) + " extends past the end of buffer " + std::to_string(b));
    }
}

} // namespace

json prescan_json(const char* text, size_t size, const std::string& base, const LoadContext& ctx) {
    json root = parse_json_guarded(text, size, ctx);
    if (!root.is_object()) ctx.fail("malformed glTF: the top level is not a JSON object");
    check_required_extensions(root, ctx);
    check_uris(root, base, ctx);
    check_image_buffer_views(root, ctx);
    return root;
}

bool drop_draco_indices(json& root) {
    bool changed = false;
    auto meshes = root.find("meshes");
    if (meshes == root.end() || !meshes->is_array()) return false;
    for (json& mesh : *meshes) {
        auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
        if (!mesh.is_object() || prims == mesh.end() || !prims->is_array()) continue;
        for (json& prim : *prims) {
            if (!prim.is_object() || !prim.contains("indices")) continue;
            auto ext = prim.find("extensions");
            if (ext != prim.end() && ext->is_object() && ext->contains("KHR_draco_mesh_compression")) {
                prim.erase("indices");
                changed = true;
            }
        }
    }
    return changed;
}

std::vector<unsigned char> glb_with_json(const std::vector<unsigned char>& bytes, const std::string& text) {
    // Called on a container glb_json_chunk has checked: bytes >= 20 + old JSON chunk length.
    uint32_t old_length =
        uint32_t(bytes[12]) | uint32_t(bytes[13]) << 8 | uint32_t(bytes[14]) << 16 | uint32_t(bytes[15]) << 24;
    std::string padded = text;
    while (padded.size() % 4) padded += ' ';
    size_t rest = bytes.size() - 20 - old_length;
    std::vector<unsigned char> out(20 + padded.size() + rest);
    std::memcpy(out.data(), bytes.data(), 20);
    std::memcpy(out.data() + 20, padded.data(), padded.size());
    if (rest) std::memcpy(out.data() + 20 + padded.size(), bytes.data() + 20 + old_length, rest);
    auto put = [&](size_t at, uint64_t v) {
        for (int k = 0; k < 4; ++k) out[at + size_t(k)] = static_cast<unsigned char>(v >> (8 * k));
    };
    put(8, out.size());
    put(12, padded.size());
    return out;
}

bool is_glb(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

namespace {

uint32_t read_u32_le(const unsigned char* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

} // namespace

// The JSON chunk of a GLB container (header: magic, version, length; chunk: length, "JSON").
// tinygltf 2.7.0 checks the BIN chunk's length without its 8-byte chunk header, and then copies
// up to 8 bytes from past the end of the file: that chunk is checked here too.
std::pair<const char*, size_t> glb_json_chunk(const std::vector<unsigned char>& bytes, const LoadContext& ctx) {
    if (bytes.size() < 20 || read_u32_le(&bytes[16]) != 0x4E4F534Au) ctx.fail("invalid GLB: no JSON chunk");
    uint64_t length = read_u32_le(&bytes[12]);
    if (20 + length > bytes.size()) ctx.fail("invalid GLB: JSON chunk past the end of the file");
    uint64_t bin = 20 + length, end = std::min<uint64_t>(read_u32_le(&bytes[8]), bytes.size());
    if (bin + 8 <= end && bin + 8 + read_u32_le(&bytes[size_t(bin)]) > end)
        ctx.fail("invalid GLB: BIN chunk past the end of the file");
    return {reinterpret_cast<const char*>(&bytes[20]), size_t(length)};
}

} // namespace clppm::gltf
