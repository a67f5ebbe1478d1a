// image_io: EXR round trips bit-exactly, the PNG preview has the documented sRGB codes, and a
// failed write names the path, leaves no temp file and keeps the previous image.
#include "io/image_io.h"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sys/resource.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <stb_image.h>

#include "test_util.h"
#include "util/error.h"

namespace clppm {
namespace {

namespace fs = std::filesystem;

Image make_image(int w, int h, uint32_t seed) {
    Image img;
    img.width = w;
    img.height = h;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 100.0f);
    for (int i = 0; i < w * h * 3; ++i) img.rgb.push_back(u(rng));
    img.rgb[0] = std::numeric_limits<float>::denorm_min(); // extremes must survive too
    img.rgb[1] = std::numeric_limits<float>::max();
    return img;
}

Image solid(int w, int h, float r, float g, float b) {
    Image img;
    img.width = w;
    img.height = h;
    img.rgb.resize(size_t(w) * size_t(h) * 3);
    for (size_t i = 0; i < img.rgb.size(); i += 3) img.rgb[i] = r, img.rgb[i + 1] = g, img.rgb[i + 2] = b;
    return img;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> entries(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Decoded PNG pixels, 3 bytes each.
std::vector<unsigned char> load_png(const std::string& path, int* w, int* h) {
    int comp = 0;
    unsigned char* data = stbi_load(path.c_str(), w, h, &comp, 3);
    EXPECT_NE(data, nullptr) << path;
    if (!data) return {};
    std::vector<unsigned char> pixels(data, data + (*w) * (*h) * 3);
    stbi_image_free(data);
    return pixels;
}

// The pixels of img written as a PNG (with the tone mapping, or write_png's default) and decoded.
std::vector<unsigned char> png_pixels(const Image& img, const ToneMapping* tone = nullptr) {
    const std::string path = test::make_temp_dir("image_io") + "/img.png";
    if (tone) write_png(path, img, *tone);
    else write_png(path, img);
    int w = 0, h = 0;
    std::vector<unsigned char> px = load_png(path, &w, &h);
    EXPECT_EQ(size_t(w) * size_t(h) * 3, px.size());
    EXPECT_EQ(w, img.width);
    EXPECT_EQ(h, img.height);
    return px;
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ImageIo, ExrRoundTripIsBitExact) {
    std::string dir = test::make_temp_dir("image_io");
    Image img = make_image(7, 3, 42); // non-square: a transposed read would not match
    write_exr(dir + "/a.exr", img);
    Image back = read_exr(dir + "/a.exr");
    ASSERT_EQ(back.width, 7);
    ASSERT_EQ(back.height, 3);
    ASSERT_EQ(back.rgb.size(), img.rgb.size());
    EXPECT_EQ(std::memcmp(back.rgb.data(), img.rgb.data(), img.rgb.size() * sizeof(float)), 0);
}

TEST(ImageIo, ExrIsFloatZipWithExtraLayers) {
    std::string dir = test::make_temp_dir("image_io");
    Image img = make_image(5, 4, 1);
    std::vector<float> error(5 * 4);
    for (size_t i = 0; i < error.size(); ++i) error[i] = 0.25f * static_cast<float>(i);
    write_exr(dir + "/e.exr", img, {{"error", &error}});

    Imf::InputFile file((dir + "/e.exr").c_str());
    EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
    for (const char* name : {"R", "G", "B", "error"}) {
        const Imf::Channel* ch = file.header().channels().findChannel(name);
        ASSERT_NE(ch, nullptr) << name;
        EXPECT_EQ(ch->type, Imf::FLOAT) << name;
    }
    std::vector<float> back(error.size());
    Imf::FrameBuffer fb;
    fb.insert("error", Imf::Slice::Make(Imf::FLOAT, back.data(), file.header().dataWindow()));
    file.setFrameBuffer(fb);
    file.readPixels(0, 3);
    EXPECT_EQ(back, error);
    EXPECT_EQ(read_exr(dir + "/e.exr").rgb, img.rgb);
}

TEST(ImageIo, ExrRejectsBadLayersAndImages) {
    std::string dir = test::make_temp_dir("image_io");
    Image img = make_image(2, 2, 3);
    std::vector<float> short_layer(3);
    std::string msg = error_of([&] { write_exr(dir + "/x.exr", img, {{"error", &short_layer}}); });
    EXPECT_NE(msg.find(dir + "/x.exr"), std::string::npos) << msg;
    EXPECT_NE(msg.find("error"), std::string::npos) << msg;
    msg = error_of([&] { write_exr(dir + "/x.exr", Image{}); });
    EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
    img.rgb.pop_back();
    msg = error_of([&] { write_png(dir + "/x.png", img); });
    EXPECT_NE(msg.find("expected 12"), std::string::npos) << msg;
    EXPECT_TRUE(entries(dir).empty());
}

TEST(ImageIo, ReadExrErrors) {
    std::string dir = test::make_temp_dir("image_io");
    std::string msg = error_of([&] { read_exr(dir + "/missing.exr"); });
    EXPECT_EQ(msg.rfind("cannot read " + dir + "/missing.exr", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;

    // A luminance-only EXR: R, G, B are missing.
    std::string y_only = dir + "/y.exr";
    {
        Imf::Header header(2, 2);
        header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
        std::vector<float> y(4, 1.0f);
        Imf::FrameBuffer fb;
        fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, y.data(), header.dataWindow()));
        Imf::OutputFile out(y_only.c_str(), header);
        out.setFrameBuffer(fb);
        out.writePixels(2);
    }
    msg = error_of([&] { read_exr(y_only); });
    EXPECT_EQ(msg, "cannot read " + y_only + ": no R channel");

    std::ofstream(dir + "/junk.exr") << "not an exr";
    msg = error_of([&] { read_exr(dir + "/junk.exr"); });
    EXPECT_EQ(msg.rfind("cannot read " + dir + "/junk.exr: ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(ImageIo, SrgbCodesOfKnownValues) {
    EXPECT_EQ(linear_to_srgb8(0.0f), 0);
    EXPECT_EQ(linear_to_srgb8(0.001f), 3);  // linear toe: 12.92 * 0.001 * 255 = 3.29
    EXPECT_EQ(linear_to_srgb8(0.18f), 118); // middle grey
    EXPECT_EQ(linear_to_srgb8(0.5f), 188);
    EXPECT_EQ(linear_to_srgb8(0.8f), 231);
    EXPECT_EQ(linear_to_srgb8(1.0f), 255);
    EXPECT_EQ(linear_to_srgb8(7.0f), 255); // clamped
    EXPECT_EQ(linear_to_srgb8(-3.0f), 0);  // clamped
    EXPECT_EQ(linear_to_srgb8(std::nanf("")), 0);
}

TEST(ImageIo, PngHasSrgbValuesAndMagentaForNonFinite) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    Image img;
    img.width = 3;
    img.height = 2;
    img.rgb = {0.5f,  0.0f,  1.0f,  2.0f, -1.0f, 0.18f, nan,  0.5f, 0.5f, // top row
               0.25f, 0.25f, 0.25f, 0.5f, inf,   0.5f,  0.5f, 0.5f, -inf};
    std::vector<unsigned char> expected = {188, 0,   255, 255, 0, 118, 255, 0, 255,
                                           137, 137, 137, 255, 0, 255, 255, 0, 255};
    EXPECT_EQ(png_pixels(img), expected);
}

TEST(ImageIo, PngExposureScalesBeforeEncoding) {
    const ToneMapping clip{ToneCurve::Clip, 1.0, false};
    std::vector<unsigned char> px = png_pixels(solid(2, 2, 0.25f, 0.09f, 1.0f), &clip);
    ASSERT_EQ(px.size(), 12u);
    EXPECT_EQ(px[0], 188); // 0.25 * 2 = 0.5
    EXPECT_EQ(px[1], 118); // 0.09 * 2 = 0.18
    EXPECT_EQ(px[2], 255);
}

// The tone curve after the exposure: Reinhard at 2 x 0.5 = 1 is 0.5 (code 188), at 2 x 0.09 is
// 0.18 / 1.18; auto exposure of a uniform 0.045 grey is +2 stops, to 0.18 (code 118) under clip.
TEST(ImageIo, PngToneCurveAfterExposure) {
    const ToneMapping reinhard{ToneCurve::Reinhard, 1.0, false}, auto_clip{ToneCurve::Clip, 0.0, true};
    std::vector<unsigned char> px = png_pixels(solid(1, 1, 0.5f, 0.09f, 0.0f), &reinhard);
    ASSERT_EQ(px.size(), 3u);
    EXPECT_EQ(px[0], 188);
    EXPECT_EQ(px[1], linear_to_srgb8(float(0.18 / 1.18)));
    EXPECT_EQ(px[2], 0);
    px = png_pixels(solid(2, 1, 0.045f, 0.045f, 0.045f), &auto_clip);
    ASSERT_EQ(px.size(), 6u);
    EXPECT_EQ(px[0], 118);
}

TEST(ImageIo, WritesReplaceAtomicallyAndLeaveNoTempFiles) {
    std::string dir = test::make_temp_dir("image_io");
    write_exr(dir + "/out.exr", make_image(4, 4, 1));
    write_exr(dir + "/out.exr", make_image(4, 4, 2)); // replaces
    write_png(dir + "/out.png", solid(4, 4, 0.5f, 0.5f, 0.5f));
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"out.exr", "out.png"}));
    EXPECT_EQ(read_exr(dir + "/out.exr").rgb, make_image(4, 4, 2).rgb);
}

TEST(ImageIo, FailedWriteNamesPathAndKeepsOldFile) {
    std::string dir = test::make_temp_dir("image_io");
    std::string path = dir + "/keep.exr";
    write_exr(path, make_image(2, 2, 7));
    std::string before = read_text(path);

    // Simulate a full disk (tests run as root, so permissions cannot make writes fail): with a
    // small RLIMIT_FSIZE, write() fails with EFBIG once the temp file reaches the limit.
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit old_limit{};
    getrlimit(RLIMIT_FSIZE, &old_limit);
    rlimit small = old_limit;
    small.rlim_cur = 512;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
    std::string msg = error_of([&] { write_exr(path, make_image(64, 64, 8)); });
    std::string png_msg = error_of([&] { write_png(dir + "/keep.png", make_image(64, 64, 8)); });
    setrlimit(RLIMIT_FSIZE, &old_limit);

    EXPECT_EQ(msg, "cannot write " + path + ": " + std::strerror(EFBIG));
    EXPECT_EQ(png_msg, "cannot write " + dir + "/keep.png: " + std::strerror(EFBIG));
    EXPECT_EQ(read_text(path), before);
    EXPECT_EQ(entries(dir), std::vector<std::string>{"keep.exr"});
}

TEST(ImageIo, WriteErrorsNameThePathAndReason) {
    std::string dir = test::make_temp_dir("image_io");
    Image img = solid(2, 2, 1, 1, 1);
    std::string missing = dir + "/no/such/dir/out.exr";
    EXPECT_EQ(error_of([&] { write_exr(missing, img); }),
              "cannot write " + missing + ": directory " + dir + "/no/such/dir does not exist");

    std::ofstream(dir + "/file") << "x";
    std::string under_file = dir + "/file/out.png";
    EXPECT_EQ(error_of([&] { write_png(under_file, img); }),
              "cannot write " + under_file + ": " + dir + "/file is not a directory");

    fs::create_directory(dir + "/d.exr");
    EXPECT_EQ(error_of([&] { write_exr(dir + "/d.exr", img); }), "cannot write " + dir + "/d.exr: it is a directory");
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"d.exr", "file"}));
}

TEST(ImageIo, CheckWritable) {
    std::string dir = test::make_temp_dir("image_io");
    EXPECT_NO_THROW(check_writable(dir + "/new.exr"));
    EXPECT_TRUE(entries(dir).empty()); // the probe is removed again
    std::string msg = error_of([&] { check_writable(dir + "/missing/new.exr"); });
    EXPECT_EQ(msg, "cannot write " + dir + "/missing/new.exr: directory " + dir + "/missing does not exist");
    msg = error_of([&] { check_writable(dir); });
    EXPECT_EQ(msg, "cannot write " + dir + ": it is a directory");
}

TEST(ImageIo, PngPathFor) {
    EXPECT_EQ(png_path_for("out.exr"), "out.png");
    EXPECT_EQ(png_path_for("out"), "out.png");
    EXPECT_EQ(png_path_for("renders/v1.2/out.EXR"), "renders/v1.2/out.png");
    EXPECT_EQ(png_path_for("out.hdr"), "out.hdr.png");
}

TEST(ImageIo, Statistics) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Image img = solid(2, 2, 1.0f, 2.0f, 3.0f);
    EXPECT_EQ(count_nonfinite(img), 0u);
    EXPECT_DOUBLE_EQ(mean_radiance(img), 2.0);
    img.rgb[1] = nan;
    img.rgb[11] = std::numeric_limits<float>::infinity();
    img.rgb[10] = nan; // same pixel as the Inf: counted once
    EXPECT_EQ(count_nonfinite(img), 2u);
    EXPECT_TRUE(std::isnan(mean_radiance(img)));
    EXPECT_EQ(mean_radiance(Image{}), 0.0);
}

} // namespace
} // namespace clppm
