#include "integrators/pt_integrator.h"

#include <algorithm>
#include <chrono>

#include "device/cluster.h"
#include "device/kernel_launch.h"
#include "integrators/checkpoint_checks.h"
#include "integrators/film.h"
#include "integrators/pixel_share.h"
#include "integrators/work_balance.h"
#include "util/error.h"

namespace clppm {

namespace {

double now_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace

PtIntegrator::PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                           const cl::Program& program, const SecondaryDevices& secondaries)
    : dc_(dc), scene_(scene), settings_(settings), program_(program) {
    if (!secondaries.devices.empty()) throw Error("the path tracer renders on one device only");
    k_trace_ = cl::Kernel(program, "path_trace");
    k_film_ = cl::Kernel(program, "mean_film");
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

std::vector<std::string> PtIntegrator::warnings(const Scene& scene, const SceneFeatures& features) {
    // Roughness below 0.01 is where kernels/bsdf.cl makes the lobe a delta.
    bool smooth = false;
    for (const dev::Material& m : scene.materials)
        smooth = smooth || (m.roughness < 0.01f && (m.metallic > 0.f || m.transmission > 0.f));
    if (!smooth || !(features.point_lights || features.spot_lights || features.directional_lights)) return {};
    return {"the path tracer cannot find caustics of point, spot or directional lights through glass or mirrors: "
            "that light is missing from its image and from its error estimate (--integrator sppm finds it)"};
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
    const PixelRanges ranges = split_pixels(num_pixels_, balance_);
    const uint32_t first = ranges.first, count = ranges.count;
    if (cl.distributed()) stats_.rank_photons.assign(ranges.counts.begin(), ranges.counts.end());
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
        share_pixels(dc_.queue, accum_, 3, ranges, num_pixels_);
        if (errors_) {
            static_assert(sizeof(dev::ErrorStats) % sizeof(double) == 0, "ErrorStats is doubles");
            share_pixels(dc_.queue, errors_->statistics(), sizeof(dev::ErrorStats) / sizeof(double), ranges,
                         num_pixels_);
        }
    }
    stats_.local_work += count;
    stats_.passes += 1;
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
