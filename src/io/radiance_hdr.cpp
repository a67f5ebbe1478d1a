#include "io/radiance_hdr.h"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "util/error.h"

namespace clppm {

namespace {

// Limits no real environment map comes near: 2^15 texels a side, 2^28 texels in all.
constexpr int64_t kMaxSide = 32768, kMaxTexels = int64_t(1) << 28;

class Bytes {
public:
    explicit Bytes(std::vector<unsigned char> data) : data_(std::move(data)) {}
    unsigned char next(const char* what) {
        if (at_ >= data_.size()) throw Error(std::string("truncated: the file ends in ") + what);
        return data_[at_++];
    }
    // One header line, without its newline.
    std::string line() {
        std::string s;
        for (unsigned char c = next("the header"); c != '\n'; c = next("the header")) s += char(c);
        return s;
    }
    size_t left() const { return data_.size() - at_; }

private:
    std::vector<unsigned char> data_;
    size_t at_ = 0;
};

float channel(unsigned char m, unsigned char e) { return e ? float(m) * std::ldexp(1.0f, int(e) - 136) : 0.f; }

void put(Image& img, size_t texel, const unsigned char rgbe[4]) {
    for (int c = 0; c < 3; ++c) img.rgb[texel * 3 + size_t(c)] = channel(rgbe[c], rgbe[3]);
}

// One run-length scanline (the 4-byte marker already read): each channel in turn, runs (count >
// 128: count - 128 copies of one byte) and literals (count bytes), exactly `width` values each.
void read_rle_scanline(Bytes& in, int width, std::vector<unsigned char>& line) {
    for (int c = 0; c < 4; ++c) {
        for (int x = 0; x < width;) {
            unsigned count = in.next("a scanline");
            const bool run = count > 128;
            if (run) count -= 128;
            if (count == 0 || count > unsigned(width - x))
                throw Error("corrupt: a run crosses the end of its scanline");
            if (run) {
                const unsigned char v = in.next("a scanline");
                for (unsigned k = 0; k < count; ++k) line[size_t(x++) * 4 + size_t(c)] = v;
            } else {
                for (unsigned k = 0; k < count; ++k) line[size_t(x++) * 4 + size_t(c)] = in.next("a scanline");
            }
        }
    }
}

} // namespace

Image read_radiance_hdr(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error("cannot open the file");
    Bytes in(std::vector<unsigned char>((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>()));
    const std::string magic = in.line();
    if (magic != "#?RADIANCE" && magic != "#?RGBE") throw Error("not a Radiance HDR file (no #?RADIANCE line)");
    for (std::string l = in.line(); !l.empty(); l = in.line())
        if (l.rfind("FORMAT=", 0) == 0 && l != "FORMAT=32-bit_rle_rgbe")
            throw Error("unsupported " + l + " (only 32-bit_rle_rgbe)");
    int64_t w = 0, h = 0;
    {
        std::istringstream res(in.line());
        std::string y, x;
        if (!(res >> y >> h >> x >> w) || y != "-Y" || x != "+X")
            throw Error("unsupported resolution line (only \"-Y H +X W\", rows top first)");
    }
    if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide || w * h > kMaxTexels)
        throw Error("unsupported size " + std::to_string(w) + "x" + std::to_string(h));
    // Before allocating for the size the header claims: the fewest bytes W x H texels take (a
    // run-length scanline is at least its 4-byte marker and 2 bytes per run of at most 127 values
    // in each of its 4 channels).
    const int64_t scanline = w >= 8 && w < 32768 ? 4 + 8 * ((w + 126) / 127) : 4 * w;
    if (int64_t(in.left()) < scanline * h)
        throw Error("truncated: a " + std::to_string(w) + "x" + std::to_string(h) +
                    " Radiance HDR image needs at least " + std::to_string(scanline * h) +
                    " bytes of pixels, the file has " + std::to_string(in.left()));
    Image img;
    img.width = int(w), img.height = int(h);
    img.rgb.assign(size_t(w * h) * 3, 0.f);
    std::vector<unsigned char> line(size_t(w) * 4);
    bool flat = w < 8 || w >= 32768; // run-length scanlines need 8 <= W < 32768
    for (int64_t y = 0; y < h; ++y) {
        size_t x = 0;
        if (!flat) {
            unsigned char m[4];
            for (unsigned char& b : m) b = in.next("a scanline");
            if (m[0] == 2 && m[1] == 2 && !(m[2] & 0x80)) {
                if ((int64_t(m[2]) << 8 | m[3]) != w) throw Error("corrupt: a scanline of another width");
                read_rle_scanline(in, int(w), line);
                for (x = 0; x < size_t(w); ++x) put(img, size_t(y * w) + x, &line[x * 4]);
                continue;
            }
            // Not run-length: this and every later scanline is flat, the marker its first texel.
            flat = true;
            put(img, size_t(y * w), m);
            x = 1;
        }
        for (; x < size_t(w); ++x) {
            unsigned char t[4];
            for (unsigned char& b : t) b = in.next("the pixels");
            put(img, size_t(y * w) + x, t);
        }
    }
    return img;
}

} // namespace clppm
