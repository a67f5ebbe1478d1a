#include "io/half_image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <Imath/half.h>

#include "util/error.h"

namespace clppm {

namespace {

void put_u32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

uint32_t get_u32(const std::string& in, size_t at) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(static_cast<unsigned char>(in[at + i])) << (8 * i);
    return v;
}

uint32_t float_bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

} // namespace

std::string encode_half_image(const Image& img, double base_ev) {
    const size_t pixels = size_t(img.width) * size_t(img.height);
    if (img.width < 0 || img.height < 0 || img.rgb.size() != 3 * pixels)
        throw Error("the live view's image: " + std::to_string(img.rgb.size()) + " values for " +
                    std::to_string(img.width) + "x" + std::to_string(img.height) + " pixels");
    std::string out;
    out.reserve(kHalfImageHeaderBytes + 6 * pixels);
    out.append("CLH1", 4);
    put_u32(out, uint32_t(img.width));
    put_u32(out, uint32_t(img.height));
    put_u32(out, float_bits(float(base_ev)));
    const double scale = std::exp2(base_ev);
    constexpr float kHalfMax = 65504.0f;
    const uint16_t nan_bits = Imath::half(std::numeric_limits<float>::quiet_NaN()).bits();
    for (size_t i = 0; i < pixels; ++i) {
        const float* p = &img.rgb[3 * i];
        const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
        for (int c = 0; c < 3; ++c) {
            uint16_t bits = nan_bits;
            if (finite) {
                const double v = double(p[c]) * scale;
                bits = Imath::half(v > 0 ? float(std::min(v, double(kHalfMax))) : 0.0f).bits();
            }
            out.push_back(static_cast<char>(bits & 0xff));
            out.push_back(static_cast<char>(bits >> 8));
        }
    }
    return out;
}

HalfImage decode_half_image(const std::string& bytes) {
    if (bytes.size() < kHalfImageHeaderBytes || bytes.compare(0, 4, "CLH1") != 0)
        throw Error("not a clppm half-float image (no CLH1 header)");
    HalfImage h;
    h.width = get_u32(bytes, 4);
    h.height = get_u32(bytes, 8);
    const uint32_t ev = get_u32(bytes, 12);
    std::memcpy(&h.base_ev, &ev, 4);
    const size_t values = size_t(h.width) * size_t(h.height) * 3;
    if (bytes.size() != kHalfImageHeaderBytes + 2 * values)
        throw Error("clppm half-float image: " + std::to_string(bytes.size()) + " bytes for " +
                    std::to_string(h.width) + "x" + std::to_string(h.height) + " pixels");
    h.rgb.resize(values);
    for (size_t i = 0; i < values; ++i) {
        Imath::half v;
        v.setBits(uint16_t(static_cast<unsigned char>(bytes[kHalfImageHeaderBytes + 2 * i]) |
                           (static_cast<unsigned char>(bytes[kHalfImageHeaderBytes + 2 * i + 1]) << 8)));
        h.rgb[i] = float(v);
    }
    return h;
}

} // namespace clppm
