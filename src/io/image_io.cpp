#include "io/image_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <exception>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <stb_image_write.h>

#include "io/regular_file.h"
#include "util/error.h"
#include "util/text.h"

namespace clppm {
namespace {

// OpenEXR messages can span lines; clppm's errors are one line.
std::string one_line(const char* what) {
    std::string s(what);
    std::replace(s.begin(), s.end(), '\n', ' ');
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
}

// OpenEXR encodes into memory so that the bytes reach disk through write_file_atomic like every
// other output, instead of OpenEXR opening (and half-writing) the target itself.
class MemoryOStream : public Imf::OStream {
public:
    explicit MemoryOStream(const std::string& name) : Imf::OStream(name.c_str()) {}
    void write(const char c[], int n) override {
        size_t end = pos_ + static_cast<size_t>(n);
        if (end > bytes.size()) bytes.resize(end);
        std::memcpy(&bytes[pos_], c, static_cast<size_t>(n));
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }
    std::string bytes;

private:
    size_t pos_ = 0;
};

void check_image(const std::string& path, const Image& img) {
    if (img.width <= 0 || img.height <= 0)
        throw Error("cannot write " + path + ": image is empty (" + std::to_string(img.width) + "x" +
                    std::to_string(img.height) + ")");
    size_t expected = static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3;
    if (img.rgb.size() != expected)
        throw Error("cannot write " + path + ": image has " + std::to_string(img.rgb.size()) + " values, expected " +
                    std::to_string(expected));
}

void check_layer(const std::string& path, const Image& img, const ExrLayer& layer) {
    const std::string& name = layer.first;
    if (name.empty() || name == "R" || name == "G" || name == "B")
        throw Error("cannot write " + path + ": invalid extra layer name '" + name + "'");
    size_t expected = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    if (!layer.second || layer.second->size() != expected)
        throw Error("cannot write " + path + ": layer '" + name + "' has " +
                    std::to_string(layer.second ? layer.second->size() : 0) + " values, expected " +
                    std::to_string(expected));
}

std::string encode_exr(const std::string& path, const Image& img, const std::vector<ExrLayer>& layers) {
    Imf::Header header(img.width, img.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [name, value] : img.attributes) header.insert(name, Imf::StringAttribute(value));
    Imf::FrameBuffer frame;
    const size_t pixel = 3 * sizeof(float);
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, img.rgb.data() + c, header.dataWindow(), pixel));
    }
    for (const ExrLayer& layer : layers) {
        header.channels().insert(layer.first, Imf::Channel(Imf::FLOAT));
        frame.insert(layer.first, Imf::Slice::Make(Imf::FLOAT, layer.second->data(), header.dataWindow()));
    }
    MemoryOStream stream(path);
    {
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame);
        file.writePixels(img.height);
    } // the destructor writes the line offset table
    return std::move(stream.bytes);
}

bool is_finite_pixel(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

std::vector<unsigned char> to_srgb8(const Image& img, const ToneMapping& tone) {
    const double scale = std::exp2(applied_exposure_ev(tone, img));
    static const unsigned char kMagenta[3] = {255, 0, 255};
    size_t pixels = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    std::vector<unsigned char> out(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) {
        const float* p = &img.rgb[3 * i];
        bool finite = is_finite_pixel(p);
        for (int c = 0; c < 3; ++c)
            out[3 * i + c] = finite ? linear_to_srgb8(float(tone_curve(tone.curve, p[c] * scale))) : kMagenta[c];
    }
    return out;
}

void append_bytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
}

void read_rgb(Imf::InputFile& file, Image& img) {
    const Imath::Box2i& window = file.header().dataWindow();
    img.width = window.max.x - window.min.x + 1;
    img.height = window.max.y - window.min.y + 1;
    img.rgb.assign(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3, 0.0f);
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, img.rgb.data() + c, window, 3 * sizeof(float)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
}

} // namespace

unsigned char linear_to_srgb8(float linear) {
    double v = linear > 0.0f ? std::min(linear, 1.0f) : 0.0; // also maps NaN to 0
    // sRGB OETF (IEC 61966-2-1): linear toe below 0.0031308, 2.4 power above.
    double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    return static_cast<unsigned char>(std::lround(encoded * 255.0));
}

void write_exr(const std::string& path, const Image& img, const std::vector<ExrLayer>& extra_layers) {
    check_image(path, img);
    for (const ExrLayer& layer : extra_layers) check_layer(path, img, layer);
    std::string bytes;
    try {
        bytes = encode_exr(path, img, extra_layers);
    } catch (const std::exception& e) {
        throw Error("cannot write " + path + ": " + one_line(e.what()));
    }
    write_file_atomic(path, bytes);
}

std::string encode_png(const Image& img, const ToneMapping& tone) {
    check_image("the PNG", img);
    std::vector<unsigned char> pixels = to_srgb8(img, tone);
    std::string bytes;
    if (!stbi_write_png_to_func(append_bytes, &bytes, img.width, img.height, 3, pixels.data(), img.width * 3))
        throw Error("PNG encoding failed");
    return bytes;
}

void write_png(const std::string& path, const Image& img, const ToneMapping& tone) {
    check_image(path, img);
    std::string bytes;
    try {
        bytes = encode_png(img, tone);
    } catch (const Error&) {
        throw Error("cannot write " + path + ": PNG encoding failed");
    }
    write_file_atomic(path, bytes);
}

Image read_exr(const std::string& path) {
    if (const std::string why = not_a_regular_file(path); !why.empty()) throw Error("cannot read " + path + ": " + why);
    Image img;
    try {
        Imf::InputFile file(path.c_str());
        for (const char* name : {"R", "G", "B"})
            if (!file.header().channels().findChannel(name))
                throw Error("cannot read " + path + ": no " + name + " channel");
        read_rgb(file, img);
        for (auto it = file.header().begin(); it != file.header().end(); ++it)
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                img.attributes[it.name()] = s->value();
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("cannot read " + path + ": " + one_line(e.what()));
    }
    return img;
}

std::string png_path_for(const std::string& exr_path) {
    if (ends_with_ci(exr_path, ".exr")) return exr_path.substr(0, exr_path.size() - 4) + ".png";
    return exr_path + ".png";
}

size_t count_nonfinite(const Image& img) {
    size_t count = 0;
    for (size_t i = 0; i + 2 < img.rgb.size(); i += 3) count += !is_finite_pixel(&img.rgb[i]);
    return count;
}

size_t count_negative(const Image& img) {
    size_t count = 0;
    for (size_t i = 0; i + 2 < img.rgb.size(); i += 3)
        count += img.rgb[i] < 0.f || img.rgb[i + 1] < 0.f || img.rgb[i + 2] < 0.f;
    return count;
}

double mean_radiance(const Image& img) {
    if (img.rgb.empty()) return 0.0;
    double sum = 0.0;
    for (float v : img.rgb) sum += v;
    return sum / static_cast<double>(img.rgb.size());
}

} // namespace clppm
