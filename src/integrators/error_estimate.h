// Progressive error estimation for photon density estimation (Hachisuka, Jarosz and Jensen,
// SIGGRAPH Asia 2010), for SPPM and PPPM: per pixel, a bound E on |L_i - L| that holds with a
// chosen confidence, the sum of an estimated bias and a Student-t bound on the noise (the
// formulas are in kernels/error_estimate.cl). The image-level error that --target-error halts on
// is a percentile of the per-pixel bounds relative to the pixel radiance.
#pragma once
#include <cstdint>
#include <map>
#include <vector>

#include "device/cl.h"
#include "device/device.h"
#include "integrators/error_image.h"
#include "integrators/integrator_stats.h"
#include "io/image_io.h"
#include "shared_types.h"

namespace clppm {

// P(Z <= z) = p for the standard normal; p in (0, 1).
double normal_quantile(double p);
// P(T <= t) = p for Student's t with nu > 0 degrees of freedom (nu = +Inf: the normal).
double student_t_quantile(double p, double nu);
// The half-width multiplier of a two-sided interval at `confidence` from n samples:
// t_{n-1}((1 + confidence) / 2). +Inf for n < 2.
double confidence_multiplier(double confidence, uint64_t n);

// E / max(L, kRelativeFloor * mean L) per pixel.
std::vector<float> relative_bounds(const std::vector<float>& absolute, const std::vector<float>& luminance);
// The expected `percentile` quantile over pixels of the actual relative error |L_i - L| / d_i
// (d_i = max(L_i, kRelativeFloor * mean L)) when pixel i's error is bias_i + sigma_i Z, Z standard
// normal: the q where the mean over pixels of P(|bias_i + sigma_i Z| > q d_i) is 1 - percentile.
// An empty `bias` means none. +Inf when any sigma is +Inf or NaN.
double expected_image_error(const std::vector<float>& sigma, const std::vector<float>& bias,
                            const std::vector<float>& luminance, double percentile = kErrorPercentile);
// The calibrated estimate multiplies expected_image_error (of sigma_i / c4(n) and the de-noised
// bias) by a factor so that the actual error at a stop lies in [0.5, 1] times the estimate. For
// the estimates from a running sum of one sample per pixel and pass (the path tracer, VCM, BPT),
// which have no bias term, 1.3: first fitted on the photon integrators against SPPM references
// (the middle of 1.19 to 1.44), it puts the path tracer at 1.20 to 1.91 times the actual error
// and VCM and BPT at 1.25 to 1.59 (bench/ERROR_CALIBRATION.md).
constexpr double kErrorCalibration = 1.3;
// For PPM, SPPM and PPPM, whose estimate adds the bias term counted only where it is significant
// (kernels/error_bound.cl): the factors that put every row against unbiased references in the
// band are 1.30 to 1.49 (two boxes against BPT, the skylit room and the doorway against the path
// tracer, 4 to 1024 passes; bench/ERROR_CALIBRATION.md, "The bias term where the photons are
// few"), and 1.4 is their middle.
constexpr double kPhotonErrorCalibration = 1.4;
// c4(n) = E[s] / sigma for the sample standard deviation s of n normal samples: the estimate
// divides by it, or it would be low by 8% at n = 4.
double c4(uint64_t n);
// The `percentile` quantile (nearest rank) of v; +Inf for an empty v or when it is not finite.
double image_error(std::vector<float> v, double percentile = kErrorPercentile);

// The device side: the Laplacian gather's output (per hit point), the per-pixel ErrorStats and
// the bound image; for the path tracer only the statistics of its passes (unbiased: no bias term). A pixel's hit points: SPPM's visible point p (no pixel_first), or PPM's
// [pixel_first[p], pixel_first[p + 1]) with `spp` samples per pixel and its constant seen emission.
struct PixelHitpoints {
    bool path_traced = false;   // the path tracer: no hit points, statistics from its running sums
    bool sobol = false;         // ... with Sobol' points over the passes (kernels/pt_error.cl)
    uint32_t num_hitpoints = 0; // 0: one per pixel
    cl::Buffer pixel_first;     // PPM: num_pixels + 1 offsets
    cl::Buffer emitted;         // PPM: float4 seen emission summed over the pixel's samples
    unsigned spp = 1;
};

class ErrorEstimator {
public:
    ErrorEstimator(const DeviceContext& dc, const cl::Program& program, uint32_t num_pixels, IntegratorStats& stats,
                   const PixelHitpoints& layout = PixelHitpoints());

    // The second gather (PhotonMap::set_second_gather) and the buffer it fills.
    const cl::Kernel& gather_kernel() const { return k_gather_; }
    const cl::Buffer& laplacian() const { return laplacian_; }

    // Fresh statistics (at the start, or resuming a checkpoint that has none), from the hit
    // statistics, or for the path tracer from its running RGB sums.
    void reset(const cl::Buffer& source);
    // The path tracer: a pass's growth of its running sums, over pixels [first, first + count)
    // only (all: count = the pixel count), a rank's share (device/cluster.h).
    void update_accum(const cl::Buffer& accum, uint32_t first, uint32_t count);
    // After a pass's gathers and before ppm_update: hit_stats still hold this pass's radii.
    // global_r2 > 0 is PPPM's radius; power_per_photon = total power / photons per pass.
    void update(const cl::Buffer& passflux, const cl::Buffer& hitpoints, const cl::Buffer& hit_stats, double global_r2,
                double power_per_photon);
    // The bounds at `confidence` in (0, 1). min_sigma: per pixel, a lower limit on the standard
    // deviation of its error that the passes' spread cannot see (PPM's fixed samples).
    // scale_variance: the relative variance of a factor common to every pixel that the passes
    // share, so their spread cannot see it either (visual importance's estimated visible fraction,
    // PhotonMappingIntegrator::normalization_variance): sigma_i^2 gains scale_variance L_i^2.
    ErrorImage estimate(double confidence, int width, int height, const std::vector<float>* min_sigma = nullptr,
                        double scale_variance = 0);

    std::vector<dev::ErrorStats> read() const;
    const cl::Buffer& statistics() const { return error_stats_; }
    // Device bytes per pixel: the Laplacian sums, the statistics and the bound image.
    static constexpr size_t bytes_per_pixel() { return sizeof(cl_long) + sizeof(dev::ErrorStats) + sizeof(cl_float8); }
    void write(const std::vector<dev::ErrorStats>& v);

private:
    const DeviceContext& dc_;
    IntegratorStats& stats_;
    uint32_t n_;
    PixelHitpoints layout_;
    uint64_t passes_ = 0;
    // Sobol' passes: the pooled half-split variance over the independent-pass variance, by
    // power-of-two count (sobol_gain).
    std::map<uint64_t, double> sobol_raw_gain_;
    cl::Kernel k_gather_, k_reset_, k_update_, k_bound_;
    cl::Buffer laplacian_, error_stats_, bound_;
};

// The error's decay, fitted as error ~ c passes^-k over the recent passes, for an ETA.
class ErrorTrend {
public:
    void add(uint64_t pass, double seconds, double error);
    // Seconds until the fitted error reaches `target` at the recent pace; 0 when already there,
    // negative when unknown (too few finite points, or the error is not decreasing).
    double eta_seconds(double target) const;

private:
    struct Point {
        double pass, seconds, error;
    };
    std::vector<Point> points_;
};

// A false-colour picture of v (blue 0, through cyan, green and yellow, to red at `scale` and
// above; NaN and Inf magenta), for the --error-output PNG.
Image false_colour(const std::vector<float>& v, int width, int height, double scale);

} // namespace clppm
