// The live view's half-float image (io/half_image.h): the layout the page reads, the exposure it
// carries, and what it does at the extremes of a float (any light power stays exact relative to
// its exposure; a value beyond binary16 saturates; a NaN pixel stays recognisable).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "io/half_image.h"
#include "util/error.h"

using namespace clppm;

namespace {

Image image_of(int w, int h, std::vector<float> rgb) {
    Image img;
    img.width = w, img.height = h;
    img.rgb = std::move(rgb);
    return img;
}

} // namespace

TEST(HalfImage, TheLayoutIsTheDocumentedOne) {
    const std::string b = encode_half_image(image_of(2, 1, {1, 0.5f, 2, 0, 0.25f, 65504}), 0.0);
    ASSERT_EQ(b.size(), kHalfImageHeaderBytes + 2 * 6);
    EXPECT_EQ(b.substr(0, 4), "CLH1");
    EXPECT_EQ(b[4], 2); // width, little-endian
    EXPECT_EQ(b[8], 1); // height
    float ev = -1;
    std::memcpy(&ev, b.data() + 12, 4);
    EXPECT_EQ(ev, 0.0f);
    // 1.0 is 0x3c00, 0.5 0x3800, 2.0 0x4000, 0.25 0x3400, 65504 0x7bff: little-endian pairs.
    const unsigned char expected[12] = {0x00, 0x3c, 0x00, 0x38, 0x00, 0x40, 0x00, 0x00, 0x00, 0x34, 0xff, 0x7b};
    EXPECT_EQ(std::memcmp(b.data() + kHalfImageHeaderBytes, expected, 12), 0);
    const HalfImage h = decode_half_image(b);
    EXPECT_EQ(h.width, 2u);
    EXPECT_EQ(h.height, 1u);
    EXPECT_EQ(h.rgb, (std::vector<float>{1, 0.5f, 2, 0, 0.25f, 65504}));
}

// The exposure is applied before the conversion, so a scene at any power a float holds arrives
// with binary16's relative precision (11 bits), not flushed to zero or infinity.
TEST(HalfImage, AnyLightPowerKeepsItsPrecision) {
    for (const double power : {1e-30, 1e-12, 1.0, 1e12, 1e30}) {
        const Image img = image_of(1, 1, {float(0.18 * power), float(0.9 * power), float(0.01 * power)});
        const double ev = -std::log2(power);
        const HalfImage h = decode_half_image(encode_half_image(img, ev));
        EXPECT_FLOAT_EQ(h.base_ev, float(ev));
        for (int c = 0; c < 3; ++c) {
            const double want = img.rgb[c] * std::exp2(ev);
            EXPECT_NEAR(h.rgb[c], want, want * std::ldexp(1.0, -11)) << "power " << power << " channel " << c;
        }
    }
}

TEST(HalfImage, ExtremesSaturateOrAreMarked) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const Image img = image_of(3, 1, {1e6f, -3.0f, 1e-9f, nan, 1, 1, 1, inf, 1});
    const HalfImage h = decode_half_image(encode_half_image(img, 0.0));
    EXPECT_EQ(h.rgb[0], 65504.0f);                                      // saturates at binary16's largest finite value
    EXPECT_EQ(h.rgb[1], 0.0f);                                          // negative: nothing to show
    EXPECT_EQ(h.rgb[2], 0.0f);                                          // below binary16's smallest subnormal
    for (int i = 3; i < 9; ++i) EXPECT_TRUE(std::isnan(h.rgb[i])) << i; // both pixels, all channels
}

TEST(HalfImage, ForeignOrTruncatedBuffersAreRefused) {
    const std::string good = encode_half_image(image_of(2, 2, std::vector<float>(12, 1)), 0.0);
    for (const std::string& bad :
         {std::string(), std::string("CLH1"), good.substr(0, good.size() - 1), "XXXX" + good.substr(4), good + "x"}) {
        try {
            decode_half_image(bad);
            ADD_FAILURE() << "accepted " << bad.size() << " bytes";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("half-float image"), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(encode_half_image(image_of(2, 2, std::vector<float>(11, 1)), 0.0), Error);
}
