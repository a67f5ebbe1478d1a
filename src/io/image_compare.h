// How far an image is from a reference (`clppm compare`, cli/compare_command.h), in the metrics
// the benchmarks report (relative MSE of the radiance, RMSE of the tonemapped image), with a count of
// non-finite pixels and an optional false-colour difference image.
#pragma once
#include <string>

#include "io/image_io.h"

namespace clppm {

struct ImageDifference {
    size_t pixels = 0;
    size_t nonfinite_a = 0, nonfinite_b = 0;
    double mean_a = 0, mean_b = 0; // mean radiance
    double rel_mse = 0;            // mean over pixels and channels of (a-b)^2 / (b^2 + 1e-2)
    double rmse = 0;               // of the radiance
    double rel_rmse = 0;           // rmse / mean_b
    double rmse_srgb = 0;          // of the 8-bit-style tonemapped images, in [0, 1]
    // The measure --target-error states: the 90th percentile over pixels of |Y_a - Y_b| /
    // max(Y_b, 1% of the mean Y_b), on luminance Y (Rec. 709 weights).
    double p90_rel_error = 0;
};

// Compares a with the reference b (same size, or Error naming both sizes). Non-finite pixels are
// counted and left out of the error sums.
ImageDifference compare_images(const Image& a, const Image& b);

// |a - b| per pixel (mean over channels) in false colour, scaled so that `scale` is the top of
// the colour ramp (black, blue, green, yellow, red); 0 picks the 99th percentile.
Image difference_image(const Image& a, const Image& b, double scale = 0);

// The mean over k x k blocks of pixels (a remainder of fewer than k rows or columns is left out):
// compared with a reference, it measures bias rather than pixel noise.
Image box_filter(const Image& a, int k);

} // namespace clppm
