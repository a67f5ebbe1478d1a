// glTF 2.0 -> Scene. Three stages: a guarded pre-scan of the raw JSON (nesting depth, required
// extensions, URIs, image buffer views: the checks tinygltf does not make before it touches
// memory or the file system), parsing with tinygltf behind file-system callbacks that stay inside
// the scene's directory, then flattening the node hierarchy into world-space triangles.
#include "gltf_load.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <type_traits>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include "embedded_files.h"
#include "error.h"

namespace clppm {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Limits that turn hostile or broken input into an error instead of a huge allocation or a hang.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;   // any one file read
constexpr uint64_t kMaxExternalBytes = uint64_t(1) << 31; // all external files together
constexpr uint64_t kMaxAccessorCount = uint64_t(1) << 31;
constexpr size_t kMaxTriangles = size_t(1) << 25;        // ~3.3 GB of host triangle data
constexpr size_t kMaxNodeVisits = size_t(1) << 20;       // shared subtrees instanced many times
constexpr size_t kMaxTexels = size_t(1) << 26;           // 1 GiB of float4 texels, all images
constexpr int kMaxImageSide = 16384;
constexpr int kMaxJsonDepth = 64;                        // tinygltf converts extras recursively
constexpr size_t kMaxByteStride = 252;                   // glTF 2.0 limit
constexpr double kPi = 3.14159265358979323846;

const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_transmission",
    "KHR_materials_ior"};

// ---- messages -------------------------------------------------------------------------------

// Error messages are one line: tinygltf and nlohmann texts are joined with "; ".
std::string one_line(const std::string& text) {
    std::string out;
    bool pending_break = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pending_break = !out.empty();
            continue;
        }
        if (pending_break) out += "; ";
        pending_break = false;
        out += (c == '\t') ? ' ' : c;
    }
    return out;
}

// tinygltf quotes whole data URIs in its errors: keep messages readable.
std::string clipped(const std::string& text, size_t max_chars = 300) {
    return text.size() <= max_chars ? text : text.substr(0, max_chars) + "...";
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line != "\r") lines.push_back(one_line(line));
    return lines;
}

class LoadContext {
public:
    LoadContext(std::string source, Scene* scene) : source_(std::move(source)), scene_(scene) {}
    const std::string& source() const { return source_; }

    [[noreturn]] void fail(const std::string& what) const { throw Error(source_ + ": " + what); }

    // Each distinct warning once: instanced meshes would otherwise repeat theirs.
    void warn(const std::string& what) {
        if (seen_.insert(what).second) scene_->warnings.push_back(what);
    }

private:
    std::string source_;
    Scene* scene_;
    std::set<std::string> seen_;
};

std::string labelled(const char* kind, int index, const std::string& name) {
    std::string s = std::string(kind) + " " + std::to_string(index);
    return name.empty() ? s : s + " ('" + name + "')";
}

// ---- file access ----------------------------------------------------------------------------

// The bytes of a file; on failure an empty vector and the reason in *why (empty on success).
std::vector<unsigned char> read_whole_file(const std::string& path, std::string* why) {
    std::error_code ec;
    *why = "";
    if (!fs::exists(path, ec)) *why = "No such file or directory";
    else if (!fs::is_regular_file(path, ec)) *why = "not a regular file";
    uint64_t size = why->empty() ? fs::file_size(path, ec) : 0;
    if (why->empty() && ec) *why = ec.message();
    if (why->empty() && size > kMaxFileBytes) *why = "larger than 1 GiB";
    if (!why->empty()) return {};
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes(static_cast<size_t>(size));
    if (!in || (size && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))) {
        *why = "read error";
        return {};
    }
    return bytes;
}

// True when `path` lies inside directory `base` (both compared lexically, after normalisation).
bool path_inside(const std::string& path, const std::string& base) {
    if (base.empty()) return false;
    fs::path rel = fs::path(path).lexically_normal().lexically_relative(base);
    return !rel.empty() && rel != "." && *rel.begin() != "..";
}

// The same after resolving symbolic links: a link inside the directory may not lead out of it.
bool resolves_inside(const std::string& path, const std::string& base) {
    std::error_code ec, base_ec;
    fs::path real = fs::weakly_canonical(path, ec), real_base = fs::weakly_canonical(base, base_ec);
    return !ec && !base_ec && path_inside(real.string(), real_base.string());
}

std::string absolute_dir(const std::string& dir) {
    std::error_code ec;
    fs::path p = dir.empty() ? fs::current_path(ec) : fs::absolute(dir, ec);
    p = p.lexically_normal();
    if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
    return p.string();
}

// tinygltf file-system callbacks: every external file must lie inside the scene's directory
// (this also stops tinygltf's fallback search of the working directory).
struct FsGuard {
    std::string base;        // absolute; empty: no external files at all
    uint64_t bytes_read = 0; // many buffers may name the same big file
};

bool guarded_file_exists(const std::string& path, void* user) {
    const auto* guard = static_cast<const FsGuard*>(user);
    std::error_code ec;
    return path_inside(path, guard->base) && fs::is_regular_file(path, ec);
}

std::string unexpanded_path(const std::string& path, void*) { return path; }

bool guarded_read_file(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                       void* user) {
    auto* guard = static_cast<FsGuard*>(user);
    std::string why = "outside the scene directory";
    if (path_inside(path, guard->base) && !resolves_inside(path, guard->base))
        why = "a symbolic link that leads outside the scene directory";
    else if (path_inside(path, guard->base)) *out = read_whole_file(path, &why);
    guard->bytes_read += out->size();
    if (why.empty() && guard->bytes_read > kMaxExternalBytes) why = "external files exceed 2 GiB in total";
    if (why.empty()) return true;
    out->clear();
    if (err) *err += path + ": " + why + "\n";
    return false;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "clppm never writes glTF files\n";
    return false;
}

// ---- pre-scan of the raw JSON ---------------------------------------------------------------

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

void check_uri(const std::string& uri, const std::string& owner, const std::string& base,
               const LoadContext& ctx) {
    if (tinygltf::IsDataURI(uri)) return;
    std::string path = url_decode(uri);
    std::string bad = owner + " URI '" + uri + "'";
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
                check_uri(uri->get<std::string>(), std::string(section, strlen(section) - 1) + " " +
                          std::to_string(i), base, ctx);
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
            ctx.fail("bufferView " + std::to_string(v) + " extends past the end of buffer " +
                     std::to_string(b));
    }
}

void prescan_json(const char* text, size_t size, const std::string& base, const LoadContext& ctx) {
    json root = parse_json_guarded(text, size, ctx);
    if (!root.is_object()) ctx.fail("malformed glTF: the top level is not a JSON object");
    check_required_extensions(root, ctx);
    check_uris(root, base, ctx);
    check_image_buffer_views(root, ctx);
}

bool is_glb(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

uint32_t read_u32_le(const unsigned char* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

// The JSON chunk of a GLB container (header: magic, version, length; chunk: length, "JSON").
// tinygltf 2.7.0 checks the BIN chunk's length without its 8-byte chunk header, and then copies
// up to 8 bytes from past the end of the file: that chunk is checked here too.
std::pair<const char*, size_t> glb_json_chunk(const std::vector<unsigned char>& bytes,
                                              const LoadContext& ctx) {
    if (bytes.size() < 20 || read_u32_le(&bytes[16]) != 0x4E4F534Au)
        ctx.fail("invalid GLB: no JSON chunk");
    uint64_t length = read_u32_le(&bytes[12]);
    if (20 + length > bytes.size()) ctx.fail("invalid GLB: JSON chunk past the end of the file");
    uint64_t bin = 20 + length, end = std::min<uint64_t>(read_u32_le(&bytes[8]), bytes.size());
    if (bin + 8 <= end && bin + 8 + read_u32_le(&bytes[size_t(bin)]) > end)
        ctx.fail("invalid GLB: BIN chunk past the end of the file");
    return {reinterpret_cast<const char*>(&bytes[20]), size_t(length)};
}

// ---- images ---------------------------------------------------------------------------------

// Decoded pixels so far: compressed images are small, so the budget is on what they expand to.
struct ImageDecoder {
    LoadContext* ctx;
    size_t texels = 0;
};

// tinygltf image callback: decodes to 8-bit RGBA. A failure is a warning (the material loses its
// texture), not an error, and oversized images are refused before stb allocates for them.
bool decode_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                  const unsigned char* bytes, int size, void* user) {
    auto* decoder = static_cast<ImageDecoder*>(user);
    std::string label = labelled("image", index, image->name);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) {
        decoder->ctx->warn(label + " could not be decoded (" + stbi_failure_reason() + "); texture ignored");
        return true;
    }
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide || decoder->texels + size_t(w) * h > kMaxTexels) {
        decoder->ctx->warn(label + " is " + std::to_string(w) + "x" + std::to_string(h) +
                           ", over the 2^26 texel budget; texture ignored");
        return true;
    }
    unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &comp, 4);
    if (!pixels) {
        decoder->ctx->warn(label + " could not be decoded (" + stbi_failure_reason() + "); texture ignored");
        return true;
    }
    decoder->texels += size_t(w) * h;
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels, pixels + size_t(w) * h * 4);
    stbi_image_free(pixels);
    return true;
}

// ---- parsing --------------------------------------------------------------------------------

tinygltf::Model parse_model(const std::vector<unsigned char>& bytes, const std::string& base,
                            LoadContext& ctx) {
    bool glb = is_glb(bytes);
    auto [text, text_size] = glb ? glb_json_chunk(bytes, ctx)
                                 : std::make_pair(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    prescan_json(text, text_size, base, ctx);

    FsGuard guard{base};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&guarded_file_exists, &unexpanded_path, &guarded_read_file, &refuse_write, &guard});
    ImageDecoder decoder{&ctx};
    loader.SetImageLoader(&decode_image, &decoder);
    tinygltf::Model model;
    std::string err, warn;
    unsigned size = unsigned(bytes.size()); // <= 1 GiB (kMaxFileBytes)
    bool ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base)
                  : loader.LoadASCIIFromString(&model, &err, &warn, text, size, base);
    for (const std::string& line : split_lines(warn)) ctx.warn(line);
    if (!ok) ctx.fail("invalid glTF: " + clipped(err.empty() ? std::string("unknown error") : one_line(err)));
    return model;
}

// ---- accessors ------------------------------------------------------------------------------

// A validated accessor: every element lies inside its buffer.
struct AccessorView {
    const unsigned char* data = nullptr; // first element
    size_t stride = 0, count = 0;
    int component_type = 0, components = 0;
    bool normalized = false;

    // Component c of element i, normalised integers mapped as in glTF 2.0 Sec. 3.11.
    double get(size_t i, int c) const {
        const unsigned char* p = data + i * stride;
        switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return scalar<int8_t>(p, c, 127.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return scalar<uint8_t>(p, c, 255.0);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return scalar<int16_t>(p, c, 32767.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return scalar<uint16_t>(p, c, 65535.0);
        case TINYGLTF_COMPONENT_TYPE_INT: return scalar<int32_t>(p, c, 2147483647.0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return scalar<uint32_t>(p, c, 4294967295.0);
        default: return scalar<float>(p, c, 1.0);
        }
    }
    uint32_t index(size_t i) const { return uint32_t(get(i, 0)); }

private:
    template <typename T> double scalar(const unsigned char* p, int c, double max) const {
        T v;
        std::memcpy(&v, p + c * sizeof(T), sizeof(T));
        if (!normalized || std::is_floating_point<T>::value) return double(v);
        return std::max(double(v) / max, -1.0);
    }
};

class AccessorReader {
public:
    AccessorReader(const tinygltf::Model& m, const LoadContext& ctx) : m_(m), ctx_(ctx) {}

    AccessorView view(int index, const std::string& what) const {
        if (index < 0 || size_t(index) >= m_.accessors.size())
            ctx_.fail(what + " accessor " + std::to_string(index) + " out of range (" +
                      std::to_string(m_.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = m_.accessors[size_t(index)];
        std::string label = "accessor " + std::to_string(index);
        if (uint64_t(a.count) > kMaxAccessorCount)
            ctx_.fail(label + " count " + std::to_string(a.count) + " exceeds the limit of 2^31");
        if (a.sparse.isSparse) ctx_.fail(label + " is sparse; sparse accessors are not supported");
        int comp_size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        int comps = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        if (comp_size <= 0 || comps <= 0 || a.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE)
            ctx_.fail(label + " has an invalid componentType or type");
        const tinygltf::BufferView& bv = buffer_view(a.bufferView, label);
        size_t elem = size_t(comp_size) * size_t(comps);
        size_t stride = bv.byteStride ? bv.byteStride : elem;
        if (stride < elem || stride > kMaxByteStride)
            ctx_.fail("bufferView " + std::to_string(a.bufferView) + " byteStride " +
                      std::to_string(bv.byteStride) + " does not fit " + label);
        // byteOffset + (count-1)*stride + elem <= byteLength, without overflow.
        if (a.byteOffset > bv.byteLength || (a.count && (a.count - 1) * stride + elem > bv.byteLength - a.byteOffset))
            ctx_.fail(label + " reads past the end of bufferView " + std::to_string(a.bufferView));
        const auto& buffer = m_.buffers[size_t(bv.buffer)].data;
        return AccessorView{buffer.data() + bv.byteOffset + a.byteOffset, stride, a.count,
                            a.componentType, comps, a.normalized};
    }

private:
    const tinygltf::BufferView& buffer_view(int index, const std::string& owner) const {
        if (index < 0 || size_t(index) >= m_.bufferViews.size())
            ctx_.fail(owner + " has no valid bufferView (" + std::to_string(index) + ")");
        const tinygltf::BufferView& bv = m_.bufferViews[size_t(index)];
        std::string label = "bufferView " + std::to_string(index);
        if (bv.buffer < 0 || size_t(bv.buffer) >= m_.buffers.size())
            ctx_.fail(label + " buffer " + std::to_string(bv.buffer) + " out of range");
        size_t size = m_.buffers[size_t(bv.buffer)].data.size();
        if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset)
            ctx_.fail(label + " extends past the end of buffer " + std::to_string(bv.buffer));
        return bv;
    }

    const tinygltf::Model& m_;
    const LoadContext& ctx_;
};

// ---- small math -----------------------------------------------------------------------------

bool finite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::dmat4 rotation_matrix(const std::vector<double>& q) {
    double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double x = q[0] / len, y = q[1] / len, z = q[2] / len, w = q[3] / len;
    glm::dmat4 r(1.0); // r[column][row]
    r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0};
    r[1] = {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0};
    r[2] = {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0};
    return r;
}

bool transform_arrays_valid(const tinygltf::Node& n) {
    auto ok = [](const std::vector<double>& v, size_t want) { return v.empty() || v.size() == want; };
    return ok(n.matrix, 16) && ok(n.translation, 3) && ok(n.rotation, 4) && ok(n.scale, 3);
}

// The node's local matrix: `matrix` (column-major) or T * R * S.
glm::dmat4 local_matrix(const tinygltf::Node& n) {
    glm::dmat4 m(1.0);
    if (!n.matrix.empty()) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c * 4 + r)];
        return m;
    }
    if (!n.translation.empty()) m[3] = {n.translation[0], n.translation[1], n.translation[2], 1.0};
    if (!n.rotation.empty()) m = m * rotation_matrix(n.rotation);
    if (!n.scale.empty())
        for (int c = 0; c < 3; ++c) m[c] *= n.scale[size_t(c)];
    return m;
}

glm::dvec3 transform_point(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }
glm::dvec3 transform_dir(const glm::dmat4& m, const glm::dvec3& d) { return glm::dvec3(m * glm::dvec4(d, 0.0)); }

// Unit vector, or (0,0,0) when v has no usable direction.
glm::dvec3 unit_or_zero(const glm::dvec3& v) {
    double len = glm::length(v);
    return (std::isfinite(len) && len > 1e-30) ? v / len : glm::dvec3(0.0);
}

void store3(float* dst, const glm::dvec3& v) {
    dst[0] = float(v.x), dst[1] = float(v.y), dst[2] = float(v.z);
}

// ---- materials ------------------------------------------------------------------------------

// 8-bit sRGB -> linear (IEC 61966-2-1).
const std::array<float, 256>& srgb_to_linear_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            double c = i / 255.0;
            t[size_t(i)] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}

// A number inside a material/texture extension object, or `fallback` when absent.
double extension_number(const tinygltf::ExtensionMap& extensions, const char* extension,
                        const char* key, double fallback) {
    auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& v = it->second.Get(key);
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// The material kind mapping documented in gltf_load.h.
uint32_t material_kind(float metallic, float roughness, float transmission) {
    if (transmission > 0.f) return MATERIAL_DIELECTRIC;
    if (metallic >= 1.f) return roughness > 0.f ? MATERIAL_GLOSSY : MATERIAL_MIRROR;
    if (metallic > 0.f) return MATERIAL_METAL_MIX;
    return MATERIAL_DIFFUSE;
}

// glTF 2.0 Sec. 5.19: the material of a primitive that names none.
dev::Material default_material() {
    dev::Material m{};
    for (int c = 0; c < 3; ++c) m.base_color[c] = 1.f;
    m.base_color[3] = 1.f;
    m.metallic = 1.f;
    m.roughness = 1.f;
    m.ior = 1.5f;
    m.base_color_tex = -1;
    m.kind = material_kind(m.metallic, m.roughness, m.transmission);
    return m;
}

// ---- flattening -----------------------------------------------------------------------------

// World-space vertex data of one primitive instance.
struct WorldVertices {
    std::vector<glm::dvec3> position;
    std::vector<glm::dvec3> normal; // empty: none in the file; (0,0,0): unusable
    std::vector<glm::vec2> uv;      // empty: none
};

class SceneBuilder {
public:
    SceneBuilder(const tinygltf::Model& m, LoadContext& ctx, Scene& s)
        : m_(m), ctx_(ctx), s_(s), reader_(m, ctx) {}

    void build() {
        warn_unsupported_extensions();
        convert_materials();
        std::vector<int> roots = root_nodes();
        // Instancing multiplies triangles: a few kilobytes of nodes can name 2^26 of them. A first
        // pass that only counts makes such a file fail before it fills gigabytes.
        counting_ = true;
        traverse(roots);
        counting_ = false;
        visits_ = 0;
        traverse(roots);
        if (s_.shading.empty()) ctx_.fail("no triangle geometry");
    }

private:
    void warn_unsupported_extensions() {
        for (const std::string& name : m_.extensionsUsed)
            if (!kSupportedExtensions.count(name)) ctx_.warn("extension " + name + " is not supported; ignored");
    }

    // -- materials --

    void convert_materials() {
        for (size_t i = 0; i < m_.materials.size(); ++i) s_.materials.push_back(convert_material(int(i)));
    }

    void copy_finite(float* dst, const std::vector<double>& src, size_t n, const std::string& what,
                     const std::string& label) {
        if (src.size() != n) ctx_.fail(label + " " + what + " must have " + std::to_string(n) + " components");
        for (size_t c = 0; c < n; ++c) {
            dst[c] = float(src[c]);
            if (!std::isfinite(dst[c])) ctx_.fail(label + " has a non-finite " + what);
        }
    }

    float finite_factor(double v, const std::string& what, const std::string& label) {
        float f = float(v);
        if (!std::isfinite(f)) ctx_.fail(label + " has a non-finite " + what);
        return f;
    }

    dev::Material convert_material(int index) {
        const tinygltf::Material& g = m_.materials[size_t(index)];
        const auto& pbr = g.pbrMetallicRoughness;
        std::string label = labelled("material", index, g.name);
        dev::Material m{};
        copy_finite(m.base_color, pbr.baseColorFactor, 4, "baseColorFactor", label);
        for (int c = 0; c < 4; ++c) m.base_color[c] = std::clamp(m.base_color[c], 0.f, 1.f);
        copy_finite(m.emission, g.emissiveFactor, 3, "emissiveFactor", label);
        float strength = finite_factor(
            extension_number(g.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0),
            "emissiveStrength", label);
        for (int c = 0; c < 3; ++c) // each factor finite as a float, their product may not be
            m.emission[c] = std::max(0.f, finite_factor(double(m.emission[c]) * strength,
                                                        "emissiveFactor * emissiveStrength", label));
        m.metallic = std::clamp(finite_factor(pbr.metallicFactor, "metallicFactor", label), 0.f, 1.f);
        m.roughness = std::clamp(finite_factor(pbr.roughnessFactor, "roughnessFactor", label), 0.f, 1.f);
        m.transmission = std::clamp(finite_factor(
            extension_number(g.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0),
            "transmissionFactor", label), 0.f, 1.f);
        m.ior = finite_factor(extension_number(g.extensions, "KHR_materials_ior", "ior", 1.5), "ior", label);
        if (m.ior < 1.f) {
            ctx_.warn(label + " ior " + std::to_string(m.ior) + " is below 1; using 1");
            m.ior = 1.f;
        }
        m.base_color_tex = texture_for(pbr.baseColorTexture, label);
        if (g.emissiveTexture.index >= 0) ctx_.warn(label + " emissiveTexture is not supported; emission is uniform");
        if (pbr.metallicRoughnessTexture.index >= 0)
            ctx_.warn(label + " metallicRoughnessTexture is not supported; factors only");
        m.flags = g.doubleSided ? MATERIAL_FLAG_DOUBLE_SIDED : 0u;
        m.kind = material_kind(m.metallic, m.roughness, m.transmission);
        return m;
    }

    uint32_t material_index(int gltf_material, const std::string& owner) {
        if (gltf_material >= 0 && size_t(gltf_material) < m_.materials.size()) return uint32_t(gltf_material);
        if (gltf_material >= 0) ctx_.fail(owner + " material " + std::to_string(gltf_material) + " out of range");
        if (default_material_ < 0) {
            default_material_ = int(s_.materials.size());
            s_.materials.push_back(default_material());
        }
        return uint32_t(default_material_);
    }

    // -- textures --

    int32_t texture_for(const tinygltf::TextureInfo& info, const std::string& label) {
        if (info.index < 0) return -1;
        if (size_t(info.index) >= m_.textures.size())
            ctx_.fail(label + " baseColorTexture " + std::to_string(info.index) + " out of range");
        if (info.texCoord != 0) {
            ctx_.warn(label + " baseColorTexture uses TEXCOORD_" + std::to_string(info.texCoord) +
                      "; only TEXCOORD_0 is supported, texture ignored");
            return -1;
        }
        if (info.extensions.count("KHR_texture_transform"))
            ctx_.warn(label + " KHR_texture_transform is not supported; ignored");
        auto cached = texture_cache_.find(info.index);
        if (cached != texture_cache_.end()) return cached->second;
        return texture_cache_[info.index] = convert_texture(info.index);
    }

    int32_t convert_texture(int index) {
        const tinygltf::Texture& t = m_.textures[size_t(index)];
        std::string label = labelled("texture", index, t.name);
        if (t.source < 0 || size_t(t.source) >= m_.images.size()) {
            ctx_.warn(label + " has no valid image source; texture ignored");
            return -1;
        }
        const tinygltf::Image& img = m_.images[size_t(t.source)];
        size_t texels = (img.width > 0 && img.height > 0) ? size_t(img.width) * size_t(img.height) : 0;
        if (texels == 0 || img.component != 4 || img.bits != 8 || img.image.size() != texels * 4) {
            ctx_.warn(label + " image " + std::to_string(t.source) + " has no decoded pixels; texture ignored");
            return -1;
        }
        if (s_.texels.size() + texels > kMaxTexels) ctx_.fail("textures exceed 2^26 texels in total");
        dev::Texture tex{uint32_t(s_.texels.size()), uint32_t(img.width), uint32_t(img.height), wrap_bits(t.sampler, label)};
        append_linear_texels(img);
        s_.textures.push_back(tex);
        return int32_t(s_.textures.size() - 1);
    }

    // Texels are stored top row first, so glTF's (u, v) (origin top left) index them directly.
    void append_linear_texels(const tinygltf::Image& img) {
        const auto& lut = srgb_to_linear_table();
        const unsigned char* p = img.image.data();
        for (size_t i = 0, n = img.image.size() / 4; i < n; ++i, p += 4)
            s_.texels.push_back({lut[p[0]], lut[p[1]], lut[p[2]], p[3] / 255.f});
    }

    uint32_t wrap_bits(int sampler, const std::string& label) {
        if (sampler < 0 || size_t(sampler) >= m_.samplers.size()) return 0; // repeat
        const tinygltf::Sampler& s = m_.samplers[size_t(sampler)];
        if (s.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT || s.wrapT == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
            ctx_.warn(label + " MIRRORED_REPEAT is not supported; using REPEAT");
        return (s.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ? 1u : 0u) |
               (s.wrapT == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ? 2u : 0u);
    }

    // -- node hierarchy --

    std::vector<int> root_nodes() {
        if (m_.scenes.empty()) return parentless_nodes();
        int scene = m_.defaultScene >= 0 ? m_.defaultScene : 0;
        if (size_t(scene) >= m_.scenes.size())
            ctx_.fail("default scene " + std::to_string(scene) + " out of range (" +
                      std::to_string(m_.scenes.size()) + " scenes)");
        return m_.scenes[size_t(scene)].nodes;
    }

    // Without a `scenes` array, render every node that is nobody's child.
    std::vector<int> parentless_nodes() {
        std::vector<char> is_child(m_.nodes.size(), 0);
        for (const auto& n : m_.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < m_.nodes.size()) is_child[size_t(c)] = 1;
        std::vector<int> roots;
        for (size_t i = 0; i < m_.nodes.size(); ++i)
            if (!is_child[i]) roots.push_back(int(i));
        return roots;
    }

    struct Frame {
        int node;
        glm::dmat4 world;
        size_t next_child;
    };

    // Depth-first with an explicit stack (no recursion limit on deep chains); a node already on
    // the current path is its own ancestor: a cycle.
    void traverse(const std::vector<int>& roots) {
        on_path_.assign(m_.nodes.size(), 0);
        for (int root : roots) {
            std::vector<Frame> stack;
            enter(root, glm::dmat4(1.0), -1, stack);
            while (!stack.empty()) {
                Frame& top = stack.back();
                const std::vector<int>& children = m_.nodes[size_t(top.node)].children;
                if (top.next_child == children.size()) {
                    on_path_[size_t(top.node)] = 0;
                    stack.pop_back();
                    continue;
                }
                int child = children[top.next_child++];
                glm::dmat4 parent = top.world; // copied: push_back may move `top`
                enter(child, parent, top.node, stack);
            }
        }
    }

    std::string node_label(int index) const { return labelled("node", index, m_.nodes[size_t(index)].name); }

    // Labels are built only on the way to an error: shared subtrees make this path hot.
    void enter(int index, const glm::dmat4& parent, int parent_index, std::vector<Frame>& stack) {
        if (index < 0 || size_t(index) >= m_.nodes.size())
            ctx_.fail((parent_index < 0 ? std::string("scene root") : node_label(parent_index) + " child") +
                      " node " + std::to_string(index) + " out of range (" + std::to_string(m_.nodes.size()) + " nodes)");
        const tinygltf::Node& node = m_.nodes[size_t(index)];
        if (on_path_[size_t(index)]) ctx_.fail("node graph cycle: " + node_label(index) + " is its own ancestor");
        if (++visits_ > kMaxNodeVisits) ctx_.fail("the node hierarchy instances more than 2^20 nodes");
        glm::dmat4 world(1.0); // the counting pass needs no transforms
        if (counting_) {
            count_triangles(node.mesh);
        } else {
            if (!transform_arrays_valid(node))
                ctx_.fail(node_label(index) + " has a transform array of the wrong length");
            glm::dmat4 local = local_matrix(node);
            world = parent * local;
            if (!finite(local) || !finite(world)) ctx_.fail(node_label(index) + " has a non-finite transform");
            instantiate(index, world);
        }
        on_path_[size_t(index)] = 1;
        stack.push_back({index, world, 0});
    }

    void instantiate(int index, const glm::dmat4& world) {
        const tinygltf::Node& node = m_.nodes[size_t(index)];
        auto light = node.extensions.find("KHR_lights_punctual");
        bool has_light = light != node.extensions.end();
        if (node.mesh == -1 && node.camera == -1 && !has_light) return;
        std::string label = node_label(index);
        if (node.mesh != -1) add_mesh(node.mesh, world, label);
        if (node.camera != -1) add_camera(node, world, label);
        if (has_light) add_light(light->second, world, label);
    }

    // -- meshes --

    // Adds the triangles an instance of `mesh` will add (an upper bound: degenerate ones count).
    void count_triangles(int mesh) {
        if (mesh < 0 || size_t(mesh) >= m_.meshes.size()) return; // add_mesh reports it
        auto cached = mesh_triangles_.find(mesh);
        if (cached == mesh_triangles_.end()) {
            size_t n = 0; // each count <= 2^31 (AccessorReader)
            const tinygltf::Mesh& g = m_.meshes[size_t(mesh)];
            for (size_t p = 0; p < g.primitives.size(); ++p) {
                const tinygltf::Primitive& prim = g.primitives[p];
                if (prim.mode != TINYGLTF_MODE_TRIANGLES || !prim.attributes.count("POSITION")) continue;
                std::string label = labelled("mesh", mesh, g.name) + " primitive " + std::to_string(p);
                size_t vertices = attribute(prim, "POSITION", label).count;
                n += (prim.indices < 0 ? vertices : reader_.view(prim.indices, label + " indices").count) / 3;
            }
            cached = mesh_triangles_.emplace(mesh, n).first;
        }
        instanced_triangles_ += cached->second;
        if (instanced_triangles_ > kMaxTriangles) ctx_.fail("the scene has more than 2^25 triangles");
    }

    void add_mesh(int mesh, const glm::dmat4& world, const std::string& node_label) {
        if (size_t(mesh) >= m_.meshes.size())
            ctx_.fail(node_label + " mesh " + std::to_string(mesh) + " out of range");
        const tinygltf::Mesh& g = m_.meshes[size_t(mesh)];
        for (size_t p = 0; p < g.primitives.size(); ++p) {
            std::string label = labelled("mesh", mesh, g.name) + " primitive " + std::to_string(p);
            const tinygltf::Primitive& prim = g.primitives[p];
            if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
                ctx_.warn(label + ": mode " + std::to_string(prim.mode) + " is not TRIANGLES; skipped");
                continue;
            }
            if (!prim.attributes.count("POSITION")) {
                ctx_.warn(label + ": no POSITION attribute; skipped");
                continue;
            }
            if (!prim.attributes.count("NORMAL") && meshes_without_normals_.insert(mesh).second)
                ++s_.meshes_without_normals;
            add_primitive(prim, world, label);
        }
    }

    AccessorView attribute(const tinygltf::Primitive& prim, const char* name, const std::string& label) {
        return reader_.view(prim.attributes.at(name), label + " " + name);
    }

    void require(bool ok, const std::string& what) {
        if (!ok) ctx_.fail(what);
    }

    WorldVertices world_vertices(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label) {
        WorldVertices v;
        AccessorView pos = attribute(prim, "POSITION", label);
        require(pos.components == 3 && pos.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT,
                label + ": POSITION must be a FLOAT VEC3 accessor");
        v.position.resize(pos.count);
        for (size_t i = 0; i < pos.count; ++i)
            v.position[i] = transform_point(world, {pos.get(i, 0), pos.get(i, 1), pos.get(i, 2)});
        if (prim.attributes.count("NORMAL")) read_normals(prim, world, label, &v);
        if (prim.attributes.count("TEXCOORD_0")) read_uvs(prim, label, &v);
        return v;
    }

    // Normals by the inverse transpose, so they stay perpendicular under non-uniform scale.
    void read_normals(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label, WorldVertices* v) {
        AccessorView n = attribute(prim, "NORMAL", label);
        require(n.components == 3 && n.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT,
                label + ": NORMAL must be a FLOAT VEC3 accessor");
        require(n.count >= v->position.size(), label + ": NORMAL has fewer elements than POSITION");
        glm::dmat3 linear(world);
        double det = glm::determinant(linear);
        glm::dmat3 normal_matrix = std::abs(det) > 1e-300 ? glm::transpose(glm::inverse(linear)) : glm::dmat3(0.0);
        v->normal.resize(v->position.size());
        for (size_t i = 0; i < v->normal.size(); ++i)
            v->normal[i] = unit_or_zero(normal_matrix * glm::dvec3(n.get(i, 0), n.get(i, 1), n.get(i, 2)));
    }

    void read_uvs(const tinygltf::Primitive& prim, const std::string& label, WorldVertices* v) {
        AccessorView t = attribute(prim, "TEXCOORD_0", label);
        bool float_or_unorm = t.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                              (t.normalized && (t.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                t.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
        require(t.components == 2 && float_or_unorm,
                label + ": TEXCOORD_0 must be a VEC2 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT");
        require(t.count >= v->position.size(), label + ": TEXCOORD_0 has fewer elements than POSITION");
        v->uv.resize(v->position.size());
        for (size_t i = 0; i < v->uv.size(); ++i) {
            v->uv[i] = {float(t.get(i, 0)), float(t.get(i, 1))};
            if (!std::isfinite(v->uv[i].x) || !std::isfinite(v->uv[i].y)) v->uv[i] = {0.f, 0.f};
        }
    }

    // Vertex indices of the primitive, three per triangle (a trailing partial triangle dropped).
    std::vector<uint32_t> triangle_indices(const tinygltf::Primitive& prim, size_t vertex_count, const std::string& label) {
        std::vector<uint32_t> idx;
        if (prim.indices < 0) {
            if (vertex_count % 3) ctx_.warn(label + ": vertex count is not a multiple of 3");
            reserve_triangles(vertex_count / 3);
            idx.resize(vertex_count / 3 * 3);
            for (size_t i = 0; i < idx.size(); ++i) idx[i] = uint32_t(i);
            return idx;
        }
        AccessorView a = reader_.view(prim.indices, label + " indices");
        std::string name = "accessor " + std::to_string(prim.indices);
        bool index_type = a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                          a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                          a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        require(a.components == 1 && index_type && !a.normalized,
                label + ": indices " + name + " must be a SCALAR of UNSIGNED_BYTE/SHORT/INT");
        if (a.count % 3) ctx_.warn(label + ": index count is not a multiple of 3");
        reserve_triangles(a.count / 3);
        idx.resize(a.count / 3 * 3);
        for (size_t i = 0; i < idx.size(); ++i) {
            idx[i] = a.index(i);
            if (idx[i] >= vertex_count)
                ctx_.fail("indices " + name + " reference vertex " + std::to_string(idx[i]) + " beyond the " +
                          std::to_string(vertex_count) + " vertices of " + label + " POSITION");
        }
        return idx;
    }

    void reserve_triangles(size_t count) {
        if (count > kMaxTriangles || s_.shading.size() + count > kMaxTriangles)
            ctx_.fail("the scene has more than 2^25 triangles");
    }

    void add_primitive(const tinygltf::Primitive& prim, const glm::dmat4& world, const std::string& label) {
        uint32_t material = material_index(prim.material, label);
        WorldVertices v = world_vertices(prim, world, label);
        if (v.uv.empty() && s_.materials[material].base_color_tex >= 0)
            ctx_.warn(label + ": textured material without TEXCOORD_0; every texel lookup uses (0, 0)");
        std::vector<uint32_t> idx = triangle_indices(prim, v.position.size(), label);
        // A mirroring transform reverses the winding; swapping two vertices restores the
        // counter-clockwise front face that agrees with the (inverse-transpose) normals.
        bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
        for (size_t t = 0; t + 2 < idx.size(); t += 3) {
            std::array<uint32_t, 3> tri = {idx[t], idx[t + 1], idx[t + 2]};
            if (mirrored) std::swap(tri[1], tri[2]);
            add_triangle(tri, v, material);
        }
    }

    void add_triangle(const std::array<uint32_t, 3>& tri, const WorldVertices& v, uint32_t material) {
        Vec3 p[3];
        glm::dvec3 q[3]; // the float positions as stored, for the area test
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& w = v.position[tri[size_t(k)]];
            p[k] = {float(w.x), float(w.y), float(w.z)};
            q[k] = {p[k].x, p[k].y, p[k].z};
        }
        glm::dvec3 e1 = q[1] - q[0], e2 = q[2] - q[0], c = glm::cross(e1, e2);
        double c2 = glm::dot(c, c);
        // Zero area (or sin(angle) < 1e-7) and non-finite corners give no usable plane.
        if (!finite(q[0]) || !finite(q[1]) || !finite(q[2]) || !(c2 > 1e-14 * glm::dot(e1, e1) * glm::dot(e2, e2))) {
            ++s_.degenerate_triangles_skipped;
            return;
        }
        glm::dvec3 flat = c / std::sqrt(c2);
        dev::TriShading sh{};
        bool smooth = !v.normal.empty();
        for (int k = 0; k < 3 && smooth; ++k) smooth = v.normal[tri[size_t(k)]] != glm::dvec3(0.0);
        float* n[3] = {sh.n0, sh.n1, sh.n2};
        float* uv[3] = {sh.uv0, sh.uv1, sh.uv2};
        for (int k = 0; k < 3; ++k) {
            store3(n[k], smooth ? v.normal[tri[size_t(k)]] : flat);
            if (!v.uv.empty()) uv[k][0] = v.uv[tri[size_t(k)]].x, uv[k][1] = v.uv[tri[size_t(k)]].y;
        }
        sh.material = material;
        s_.positions.insert(s_.positions.end(), p, p + 3);
        s_.shading.push_back(sh);
    }

    // -- lights --

    void add_light(const tinygltf::Value& ext, const glm::dmat4& world, const std::string& node_label) {
        if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt())
            ctx_.fail(node_label + " KHR_lights_punctual has no light index");
        int index = ext.Get("light").GetNumberAsInt();
        if (index < 0 || size_t(index) >= m_.lights.size())
            ctx_.fail(node_label + " light " + std::to_string(index) + " out of range (" +
                      std::to_string(m_.lights.size()) + " lights)");
        const tinygltf::Light& g = m_.lights[size_t(index)];
        std::string label = labelled("light", index, g.name);
        dev::Light l{};
        if (!light_type(g.type, &l.type)) {
            ctx_.warn(label + " type '" + g.type + "' is not supported; skipped");
            return;
        }
        if (g.range > 0.0) ctx_.warn("KHR_lights_punctual range is ignored (lights reach infinitely far)");
        set_light_radiance(g, label, &l);
        glm::dvec3 dir = unit_or_zero(transform_dir(world, {0, 0, -1}));
        if (dir == glm::dvec3(0.0) && l.type != LIGHT_POINT) {
            ctx_.warn(node_label + " transform collapses the direction of " + label + "; skipped");
            return;
        }
        store3(l.position, transform_point(world, {0, 0, 0}));
        l.position[3] = 1.f;
        store3(l.direction, dir);
        set_spot_cone(g, label, &l);
        l.power = light_power(l);
        if (!std::isfinite(l.power)) ctx_.fail(label + " has a non-finite power (intensity too large)");
        s_.punctual_lights.push_back(l);
    }

    static bool light_type(const std::string& type, uint32_t* out) {
        if (type == "point") return *out = LIGHT_POINT, true;
        if (type == "spot") return *out = LIGHT_SPOT, true;
        if (type == "directional") return *out = LIGHT_DIRECTIONAL, true;
        return false;
    }

    void set_light_radiance(const tinygltf::Light& g, const std::string& label, dev::Light* l) {
        std::vector<double> color = g.color.empty() ? std::vector<double>{1.0, 1.0, 1.0} : g.color;
        if (color.size() != 3) ctx_.fail(label + " color must have 3 components");
        for (int c = 0; c < 3; ++c) {
            l->radiance[c] = float(color[size_t(c)] * g.intensity);
            if (!std::isfinite(l->radiance[c])) ctx_.fail(label + " has a non-finite color or intensity");
            if (l->radiance[c] < 0.f) ctx_.fail(label + " has a negative color or intensity");
        }
    }

    void set_spot_cone(const tinygltf::Light& g, const std::string& label, dev::Light* l) {
        if (l->type != LIGHT_SPOT) return;
        double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
        if (!std::isfinite(inner) || !std::isfinite(outer)) ctx_.fail(label + " has non-finite cone angles");
        double outer_c = std::clamp(outer, 1e-6, kPi / 2), inner_c = std::clamp(inner, 0.0, outer_c);
        if (outer_c != outer || inner_c != inner)
            ctx_.warn(label + " cone angles clamped to 0 <= inner <= outer <= pi/2");
        l->cos_inner = float(std::cos(inner_c));
        l->cos_outer = float(std::cos(outer_c));
    }

    // Emitted power (mean over RGB) that drives photon emission; directional lights get theirs
    // from the scene radius in the renderer.
    static float light_power(const dev::Light& l) {
        double mean_i = (double(l.radiance[0]) + l.radiance[1] + l.radiance[2]) / 3.0;
        if (l.type == LIGHT_POINT) return float(4.0 * kPi * mean_i);
        if (l.type == LIGHT_SPOT) return float(2.0 * kPi * mean_i * (1.0 - 0.5 * (double(l.cos_inner) + l.cos_outer)));
        return 0.f;
    }

    // -- cameras --

    void add_camera(const tinygltf::Node& node, const glm::dmat4& world, const std::string& node_label) {
        if (size_t(node.camera) >= m_.cameras.size())
            ctx_.fail(node_label + " camera " + std::to_string(node.camera) + " out of range");
        const tinygltf::Camera& g = m_.cameras[size_t(node.camera)];
        std::string label = labelled("camera", node.camera, g.name);
        if (g.type != "perspective") {
            ctx_.warn(label + " is " + g.type + "; only perspective cameras are supported, skipped");
            return;
        }
        glm::dvec3 forward = unit_or_zero(transform_dir(world, {0, 0, -1}));
        glm::dvec3 up = transform_dir(world, {0, 1, 0});
        up = unit_or_zero(up - glm::dot(up, forward) * forward); // Gram-Schmidt
        if (forward == glm::dvec3(0.0) || up == glm::dvec3(0.0)) {
            ctx_.warn(node_label + " transform collapses " + label + "; skipped");
            return;
        }
        CameraDesc c;
        c.name = g.name.empty() ? node.name : g.name;
        store3(c.position, transform_point(world, {0, 0, 0}));
        store3(c.forward, forward);
        store3(c.up, up);
        c.yfov = float(g.perspective.yfov);
        if (!(c.yfov > 0.f && c.yfov < float(kPi))) ctx_.fail(label + " yfov must lie in (0, pi)");
        c.aspect = float(g.perspective.aspectRatio);
        if (!std::isfinite(c.aspect) || c.aspect < 0.f) ctx_.fail(label + " has an invalid aspectRatio");
        c.aperture_radius = camera_extra(g, node, "aperture_radius", label);
        c.focus_distance = camera_extra(g, node, "focus_distance", label);
        s_.cameras.push_back(c);
    }

    // Thin-lens parameters from the camera's extras, else its node's; 0 when absent.
    float camera_extra(const tinygltf::Camera& cam, const tinygltf::Node& node, const char* key, const std::string& label) {
        for (const tinygltf::Value* extras : {&cam.extras, &node.extras}) {
            if (!extras->IsObject() || !extras->Has(key)) continue;
            const tinygltf::Value& v = extras->Get(key);
            float f = v.IsNumber() ? float(v.GetNumberAsDouble()) : -1.f;
            if (!std::isfinite(f) || f < 0.f) ctx_.fail(label + " extras." + key + " must be a number >= 0");
            return f;
        }
        return 0.f;
    }

    const tinygltf::Model& m_;
    LoadContext& ctx_;
    Scene& s_;
    AccessorReader reader_;
    int default_material_ = -1;
    std::map<int, int32_t> texture_cache_;
    std::set<int> meshes_without_normals_;
    std::vector<char> on_path_;
    size_t visits_ = 0;
    bool counting_ = false;           // the first traversal: count, build nothing
    size_t instanced_triangles_ = 0;  // counted so far, all instances
    std::map<int, size_t> mesh_triangles_;
};

Scene load_bytes(const std::vector<unsigned char>& bytes, const std::string& base, const std::string& source) {
    Scene scene;
    scene.source = source;
    LoadContext ctx(source, &scene);
    tinygltf::Model model = parse_model(bytes, base, ctx);
    SceneBuilder(model, ctx, scene).build();
    return scene;
}

} // namespace

Scene load_gltf(const std::string& path) {
    std::string why;
    std::vector<unsigned char> bytes = read_whole_file(path, &why);
    if (!why.empty()) throw Error(path + ": cannot open file (" + why + ")");
    return load_bytes(bytes, absolute_dir(fs::path(path).parent_path().string()), path);
}

Scene load_gltf_text(const std::string& json_text, const std::string& base_dir, const std::string& display_name) {
    if (json_text.size() > kMaxFileBytes) throw Error(display_name + ": larger than 1 GiB");
    std::vector<unsigned char> bytes(json_text.begin(), json_text.end());
    return load_bytes(bytes, base_dir.empty() ? std::string() : absolute_dir(base_dir), display_name);
}

Scene load_default_scene() {
    const char* name = "<default scene>";
    const EmbeddedFile* file = find_embedded("scenes/cornell_box.gltf");
    if (!file) throw Error(std::string(name) + ": scenes/cornell_box.gltf is not embedded in this build");
    return load_gltf_text(std::string(file->data, file->size), "", name);
}

} // namespace clppm
