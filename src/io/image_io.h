// Reading and writing rendered images: float EXR for the radiance itself, an 8-bit sRGB PNG preview
// beside it. Every write is atomic (atomic_file.h), so a failed or interrupted save never leaves a
// truncated file and never destroys the previous one.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/tone_map.h"

namespace clppm {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb; // 3 floats per pixel, row-major, top row first, linear radiance
    // Written to the EXR header as string attributes ("clppm:passes", "clppm:interrupted", ...)
    // and read back by read_exr.
    std::map<std::string, std::string> attributes;
};

// A single-channel float layer stored beside R,G,B (e.g. "error"): width*height values.
using ExrLayer = std::pair<std::string, const std::vector<float>*>;

// Float32 R,G,B (plus `extra_layers`), ZIP compression. Throws clppm::Error naming the path.
void write_exr(const std::string& path, const Image& img, const std::vector<ExrLayer>& extra_layers = {});

// 8-bit sRGB preview: each channel is scaled by 2^EV (applied_exposure_ev), put through the tone
// curve (tone_map.h) and encoded with the sRGB OETF, rounded to nearest; the default mapping is a
// plain clip at 1. A pixel with any NaN or Inf channel is drawn magenta so that it stands out.
void write_png(const std::string& path, const Image& img, const ToneMapping& tone = {});
// The same PNG as bytes in memory (the live view serves them).
std::string encode_png(const Image& img, const ToneMapping& tone = {});

// Reads R,G,B of an EXR as float; a file without all three channels is an error.
Image read_exr(const std::string& path);

// "out.exr" -> "out.png", "out" -> "out.png"; any other extension is kept: "out.hdr" ->
// "out.hdr.png", so the preview can never overwrite a file the user named.
std::string png_path_for(const std::string& exr_path);

// The 8-bit sRGB code of a linear value in [0, 1] (values outside are clamped, NaN -> 0).
unsigned char linear_to_srgb8(float linear);

// Number of pixels with at least one NaN or Inf channel.
size_t count_nonfinite(const Image& img);
// Pixels with a negative channel (radiance never is: a renderer defect).
size_t count_negative(const Image& img);

// Mean over all pixels and channels, accumulated in double. Non-finite values are included on
// purpose: a NaN in the image makes the mean NaN rather than hiding it. 0 for an empty image.
double mean_radiance(const Image& img);

} // namespace clppm
