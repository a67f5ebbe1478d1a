#include "integrators/pt_integrator.h"

#include <algorithm>
#include <chrono>

#include "device/cluster.h"
#include "device/kernel_launch.h"
#include "integrators/checkpoint_checks.h"
#include "integrators/film.h"
#include "integrators/work_balance.h"
#include "util/error.h"

namespace clppm {

namespace {

double now_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace

PtIntegrator::PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                           const cl::Program& program)
    : dc_(dc), scene_(scene), settings_(settings), program_(program) {
    k_trace_ = cl::Kernel(program, "path_trace");
    k_film_ = cl::Kernel(program, "pt_film");
    num_pixels_ = scene.camera.width * scene.camera.height;
}

namespace {

constexpr size_t kAccumBytesPerPixel = 3 * sizeof(cl_double); // the running RGB sum

} // namespace

IntegratorMemory PtIntegrator::memory_needed(size_t pixels, bool error_estimation) {
    IntegratorMemory m{pixels * (kAccumBytesPerPixel + kFilmBytesPerPixel), pixels * kAccumBytesPerPixel};
    if (error_estimation) {
        m.bytes += pixels * (sizeof(dev::ErrorStats) + sizeof(cl_float8));
        m.largest_buffer = std::max(m.largest_buffer, pixels * sizeof(dev::ErrorStats));
    }
    return m;
}

void PtIntegrator::enable_error_estimation() {
    if (errors_) return;
    PixelHitpoints layout;
    layout.path_traced = true;
    errors_ = std::make_unique<ErrorEstimator>(dc_, program_, num_pixels_, stats_, layout);
    if (accum_()) errors_->reset_accum(accum_); // after prepare(): the estimate starts here
}

ErrorImage PtIntegrator::error_estimate(double confidence) {
    if (!errors_) throw Error("error estimation is not enabled");
    return errors_->estimate(confidence, int(scene_.camera.width), int(scene_.camera.height));
}

void PtIntegrator::prepare() {
    size_t bytes = size_t(num_pixels_) * kAccumBytesPerPixel;
    accum_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, bytes);
    dc_.queue.enqueueFillBuffer(accum_, cl_double(0), 0, bytes);
    image_buf_ = cl::Buffer(dc_.context, CL_MEM_WRITE_ONLY, size_t(num_pixels_) * kFilmBytesPerPixel);
    stats_.device_bytes = bytes + size_t(num_pixels_) * kFilmBytesPerPixel;
    stats_.hitpoints = num_pixels_;
    if (errors_) errors_->reset_accum(accum_);
}

void PtIntegrator::run_pass() {
    // Each pixel's sample depends on (seed, pass, pixel) alone, so any split of the pixels gives
    // the same sums. With several processes (device/cluster.h) each rank traces a contiguous range
    // by the ranks' measured speed (integrators/work_balance.h), and the ranks then share their ranges' sums
    // and error statistics, so that every rank holds the whole image, as one process would.
    Cluster& cl = cluster();
    uint32_t first = 0, count = num_pixels_;
    std::vector<size_t> firsts, counts;
    if (cl.distributed()) {
        const std::vector<uint32_t> split = ranks_split(num_pixels_, balance_);
        size_t at = 0;
        for (uint32_t c : split) {
            firsts.push_back(at);
            counts.push_back(c);
            at += c;
        }
        first = uint32_t(firsts[size_t(cl.rank())]);
        count = uint32_t(counts[size_t(cl.rank())]);
        stats_.rank_photons.assign(counts.begin(), counts.end());
    }
    const double t0 = now_seconds();
    if (count > 0) {
        set_args(k_trace_, scene_.set_scene_args(k_trace_), scene_.camera_buf, cl_ulong(settings_.seed),
                 cl_ulong(stats_.passes + 1), cl_uint(first + count), accum_);
        cl::Event ev;
        enqueue_1d_range(dc_.queue, k_trace_, first, count, &ev);
        add_event_time(stats_, "path_trace", ev);
        if (errors_) errors_->update_accum(accum_, first, count);
    }
    collect_event_times(stats_); // waits for the pass
    if (cl.distributed()) {
        balance_.record(count, now_seconds() - t0);
        share(accum_, 3, firsts, counts);
        if (errors_) share(errors_->statistics(), sizeof(dev::ErrorStats) / sizeof(double), firsts, counts);
    }
    stats_.local_work += count;
    stats_.passes += 1;
}

void PtIntegrator::share(const cl::Buffer& buffer, size_t doubles_per_pixel, const std::vector<size_t>& firsts,
                         const std::vector<size_t>& counts) {
    static_assert(sizeof(dev::ErrorStats) % sizeof(double) == 0, "ErrorStats is doubles");
    std::vector<double> host(size_t(num_pixels_) * doubles_per_pixel);
    const size_t me = size_t(cluster().rank());
    const size_t offset = firsts[me] * doubles_per_pixel, n = counts[me] * doubles_per_pixel;
    if (n)
        dc_.queue.enqueueReadBuffer(buffer, CL_TRUE, offset * sizeof(double), n * sizeof(double), host.data() + offset);
    std::vector<size_t> f(firsts), c(counts);
    for (size_t r = 0; r < f.size(); ++r) f[r] *= doubles_per_pixel, c[r] *= doubles_per_pixel;
    cluster().share_slices(host.data(), f, c);
    write_buffer(dc_.queue, buffer, host);
}

void PtIntegrator::save(Checkpoint& ck) {
    IntegratorBase::save(ck);
    ck.put("accum", read_buffer<cl_double>(dc_.queue, accum_, size_t(num_pixels_) * 3));
    if (errors_) ck.put("error_stats2", errors_->read());
}

void PtIntegrator::restore(const Checkpoint& ck) {
    IntegratorBase::restore(ck);
    require_checkpoint_field(ck, stats_.photons_emitted == 0, "photons_emitted (a path tracer emits none)");
    std::vector<cl_double> accum = ck.get<cl_double>("accum", size_t(num_pixels_) * 3);
    check_radiance_sums(ck, accum, "accum");
    write_buffer(dc_.queue, accum_, accum);
    if (!errors_) return;
    // A checkpoint saved without error estimation: the estimate starts over from here.
    auto blob = ck.blobs.find("error_stats2");
    if (blob != ck.blobs.end() && blob->second.size() == size_t(num_pixels_) * sizeof(dev::ErrorStats))
        errors_->write(ck.get<dev::ErrorStats>("error_stats2", num_pixels_));
    else errors_->reset_accum(accum_);
}

Image PtIntegrator::image() {
    set_args(k_film_, 0, accum_, cl_uint(num_pixels_), cl_double(double(stats_.passes)), image_buf_);
    enqueue_1d(dc_.queue, k_film_, num_pixels_);
    return read_film(dc_, image_buf_, scene_.camera.width, scene_.camera.height);
}

} // namespace clppm
