#include "scene/gltf/gltf_parse.h"

#include <stb_image.h>

#include "scene/gltf/gltf_files.h"
#include "scene/gltf/gltf_prescan.h"

namespace clppm::gltf {

namespace {

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

} // namespace

tinygltf::Model parse_model(const std::vector<unsigned char>& bytes, const std::string& base, LoadContext& ctx) {
    bool glb = is_glb(bytes);
    auto [text, text_size] =
        glb ? glb_json_chunk(bytes, ctx) : std::make_pair(reinterpret_cast<const char*>(bytes.data()), bytes.size());
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

} // namespace clppm::gltf
