#include "integrators/pixel_sum_integrator.h"

#include <algorithm>

#include "device/cluster.h"
#include "device/kernel_launch.h"
#include "integrators/checkpoint_checks.h"
#include "integrators/film.h"
#include "util/error.h"
#include "util/steady_seconds.h"

namespace clppm {

PixelSumIntegrator::PixelSumIntegrator(const DeviceContext& dc, const DeviceScene& scene,
                                       const RenderSettings& settings, const cl::Program& program)
    : IntegratorBase(dc, scene, settings, program) {
    k_film_ = cl::Kernel(program, "mean_film");
}

void PixelSumIntegrator::allocate_sum() {
    const size_t sum = std::max<size_t>(size_t(num_pixels_) * kSumBytesPerPixel, 8);
    accum_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, sum);
    fill_buffer(dc_.queue, accum_, cl_double(0), 0, sum);
    const size_t film = std::max<size_t>(size_t(num_pixels_) * kFilmBytesPerPixel, 8);
    image_buf_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, film);
    stats_.device_bytes += sum + film;
    stats_.hitpoints = num_pixels_;
    if (errors_) errors_->reset(accum_);
}

IntegratorMemory PixelSumIntegrator::with_error_estimation(IntegratorMemory m, size_t pixels) {
    m.bytes += pixels * (sizeof(dev::ErrorStats) + sizeof(cl_float8));
    m.largest_buffer = std::max(m.largest_buffer, pixels * sizeof(dev::ErrorStats));
    return m;
}

void PixelSumIntegrator::enable_error_estimation() {
    if (errors_) return;
    PixelHitpoints layout;
    layout.path_traced = true;
    layout.sobol = sobol_passes();
    errors_ = std::make_unique<ErrorEstimator>(dc_, program_, num_pixels_, stats_, layout);
    if (accum_()) errors_->reset(accum_); // after prepare(): the estimate starts here
}

PixelRanges PixelSumIntegrator::begin_pass() {
    pass_start_s_ = steady_seconds();
    return split_pixels(num_pixels_, balance_);
}

// Each pixel's sample depends on (seed, pass, pixel) alone, so any split of the pixels gives the
// same sums; with several processes the ranks share the error statistics as the sums.
bool PixelSumIntegrator::passes_batchable() const { return !errors_ && !cluster().distributed(); }

void PixelSumIntegrator::end_pass(const PixelRanges& ranges, uint64_t passes) {
    if (passes != 1 && !passes_batchable()) throw Error("internal: a batch of passes where each must stand alone");
    if (errors_ && ranges.count > 0) {
        errors_->update_accum(accum_, ranges.first, ranges.count);
        collect_event_times(stats_);
    }
    if (cluster().distributed()) {
        balance_.record(ranges.count, steady_seconds() - pass_start_s_);
        share_pixels(dc_.queue, accum_, 3, ranges, num_pixels_);
        static_assert(sizeof(dev::ErrorStats) % sizeof(double) == 0, "ErrorStats is doubles");
        if (errors_)
            share_pixels(dc_.queue, errors_->statistics(), sizeof(dev::ErrorStats) / sizeof(double), ranges,
                         num_pixels_);
        stats_.rank_photons.assign(ranges.counts.begin(), ranges.counts.end());
    }
    stats_.local_work += ranges.count * passes;
    stats_.passes += passes;
}

void PixelSumIntegrator::save_sum(Checkpoint& ck) const {
    ck.put("accum", read_buffer<cl_double>(dc_.queue, accum_, size_t(num_pixels_) * 3));
    save_error_stats(ck);
}

void PixelSumIntegrator::restore_sum(const Checkpoint& ck) {
    std::vector<cl_double> accum = ck.get<cl_double>("accum", size_t(num_pixels_) * 3);
    check_radiance_sums(ck, accum, "accum");
    write_buffer(dc_.queue, accum_, accum);
    restore_error_stats(ck, accum_);
}

Image PixelSumIntegrator::image() {
    set_args(k_film_, 0, accum_, cl_uint(num_pixels_), cl_double(double(stats_.passes)), image_buf_);
    enqueue_1d(dc_.queue, k_film_, num_pixels_);
    return read_film(dc_, image_buf_, scene_.camera.width, scene_.camera.height);
}

} // namespace clppm
