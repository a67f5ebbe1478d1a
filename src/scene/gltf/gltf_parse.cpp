#include "scene/gltf/gltf_parse.h"

#include <cstring>

#include <stb_image.h>
#include <webp/decode.h>

#include "scene/gltf/gltf_files.h"
#include "scene/gltf/gltf_prescan.h"

namespace clppm::gltf {

namespace {

// Decoded pixels so far: compressed images are small, so the budget is on what they expand to.
struct ImageDecoder {
    LoadContext* ctx;
    size_t texels = 0;
};

// WebP files begin "RIFF", a 32-bit size, then "WEBP".
bool is_webp(const unsigned char* bytes, int size) {
    return size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

bool fits_budget(ImageDecoder* decoder, const std::string& label, int w, int h) {
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide || decoder->texels + size_t(w) * h > kMaxTexels) {
        decoder->ctx->warn(label + " is " + std::to_string(w) + "x" + std::to_string(h) +
                           ", over the 2^26 texel budget; texture ignored");
        return false;
    }
    return true;
}

void store_rgba8(tinygltf::Image* image, int w, int h, const unsigned char* pixels) {
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels, pixels + size_t(w) * h * 4);
}

// EXT_texture_webp images, through libwebp.
void decode_webp(tinygltf::Image* image, const std::string& label, const unsigned char* bytes, int size,
                 ImageDecoder* decoder) {
    int w = 0, h = 0;
    if (!WebPGetInfo(bytes, size_t(size), &w, &h)) {
        decoder->ctx->warn(label + " is not a valid WebP image; texture ignored");
        return;
    }
    if (!fits_budget(decoder, label, w, h)) return;
    uint8_t* pixels = WebPDecodeRGBA(bytes, size_t(size), &w, &h);
    if (!pixels) {
        decoder->ctx->warn(label + " WebP data could not be decoded; texture ignored");
        return;
    }
    decoder->texels += size_t(w) * h;
    store_rgba8(image, w, h, pixels);
    WebPFree(pixels);
}

// tinygltf image callback: decodes to 8-bit RGBA (PNG, JPEG and the rest through stb_image, WebP
// through libwebp). A failure is a warning (the material loses its texture), not an error, and
// oversized images are refused before the decoder allocates for them.
bool decode_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                  const unsigned char* bytes, int size, void* user) {
    auto* decoder = static_cast<ImageDecoder*>(user);
    std::string label = labelled("image", index, image->name);
    if (is_webp(bytes, size)) {
        decode_webp(image, label, bytes, size, decoder);
        return true;
    }
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) {
        decoder->ctx->warn(label + " could not be decoded (" + stbi_failure_reason() + "); texture ignored");
        return true;
    }
    if (!fits_budget(decoder, label, w, h)) return true;
    unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &comp, 4);
    if (!pixels) {
        decoder->ctx->warn(label + " could not be decoded (" + stbi_failure_reason() + "); texture ignored");
        return true;
    }
    decoder->texels += size_t(w) * h;
    store_rgba8(image, w, h, pixels);
    stbi_image_free(pixels);
    return true;
}

} // namespace

tinygltf::Model parse_model(const std::vector<unsigned char>& bytes, const std::string& base, LoadContext& ctx) {
    bool glb = is_glb(bytes);
    auto [text, text_size] =
        glb ? glb_json_chunk(bytes, ctx) : std::make_pair(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    nlohmann::json root = prescan_json(text, text_size, base, ctx);
    std::vector<unsigned char> rewritten; // the document tinygltf reads, when it had to change
    if (drop_draco_indices(root)) {
        std::string changed = root.dump();
        if (glb) rewritten = glb_with_json(bytes, changed);
        else rewritten.assign(changed.begin(), changed.end());
    }
    const std::vector<unsigned char>& doc = rewritten.empty() ? bytes : rewritten;

    FsGuard guard{base};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&guarded_file_exists, &unexpanded_path, &guarded_read_file, &refuse_write, &guard});
    ImageDecoder decoder{&ctx};
    loader.SetImageLoader(&decode_image, &decoder);
    tinygltf::Model model;
    std::string err, warn;
    unsigned size = unsigned(doc.size()); // <= 1 GiB (kMaxFileBytes) and a re-serialised JSON
    bool ok =
        glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, doc.data(), size, base)
            : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(doc.data()), size, base);
    for (const std::string& line : split_lines(warn)) ctx.warn(line);
    if (!ok) ctx.fail("invalid glTF: " + clipped(err.empty() ? std::string("unknown error") : one_line(err)));
    return model;
}

} // namespace clppm::gltf
