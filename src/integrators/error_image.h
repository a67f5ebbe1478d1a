// The per-pixel error bounds of progressive error estimation (integrators/error_estimate.h) and
// the image-level error --target-error halts on.
#pragma once
#include <cstdint>
#include <limits>
#include <vector>

namespace clppm {

// The image-level error is this quantile of the per-pixel relative bounds: "90% of the pixels
// are within E of the truth, each with the requested confidence". A high percentile (not the
// mean) so that a few dark pixels with huge relative error do not hold the render forever, and a
// few bright converged ones cannot hide a noisy region.
constexpr double kErrorPercentile = 0.9;
// A pixel's bound is relative to max(L, kRelativeFloor * mean L): black pixels have no
// meaningful relative error.
constexpr double kRelativeFloor = 0.01;
// --target-error stops no earlier: the spread of fewer passes says little.
constexpr uint64_t kMinPassesToStop = 4;

struct ErrorImage {
    int width = 0, height = 0;
    uint64_t passes = 0;           // passes the statistics hold
    std::vector<float> absolute;   // E per pixel, in luminance units (+Inf before two passes)
    std::vector<float> luminance;  // the pixel's estimate L_i (luminance)
    std::vector<float> bias;       // B_i, signed: > 0 where the estimate is too bright
    std::vector<float> noise;      // t sqrt(V_i / i)
    std::vector<float> sigma;      // sqrt(V_i / i): the estimated standard deviation of L_i (+Inf before two passes)
    std::vector<float> bias_clean; // B_i with the bias estimate's own noise taken out (error_bound)
    std::vector<float> bias_sigma; // sqrt(Var(B_est)), the bias estimate's own noise (0 without a bias term)
    std::vector<float> relative;   // E / max(L, floor): the per-pixel error image
    double image_error = std::numeric_limits<double>::infinity(); // kErrorPercentile of `relative`: the bound
    // The calibrated estimate of the image's actual error by the same measure (kErrorPercentile of
    // |L_i - L| / max(L, floor)): expected_image_error of the noise and de-noised bias, times
    // kErrorCalibration or kPhotonErrorCalibration (error_estimate.h).
    double expected_error = std::numeric_limits<double>::infinity();
    // PPM: the calibrated estimate from the spread of its fixed samples alone, an error more
    // passes do not remove (0 for the others).
    double sample_floor = 0;
};

} // namespace clppm
