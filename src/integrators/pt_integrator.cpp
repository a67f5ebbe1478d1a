#include "integrators/pt_integrator.h"

#include "device/kernel_launch.h"
#include "integrators/checkpoint_checks.h"
#include "integrators/film.h"

namespace clppm {

PtIntegrator::PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                           const cl::Program& program)
    : dc_(dc), scene_(scene), settings_(settings) {
    k_trace_ = cl::Kernel(program, "path_trace");
    k_film_ = cl::Kernel(program, "pt_film");
    num_pixels_ = scene.camera.width * scene.camera.height;
}

namespace {

constexpr size_t kAccumBytesPerPixel = 3 * sizeof(cl_double); // the running RGB sum

} // namespace

IntegratorMemory PtIntegrator::memory_needed(size_t pixels) {
    return {pixels * (kAccumBytesPerPixel + kFilmBytesPerPixel), pixels * kAccumBytesPerPixel};
}

void PtIntegrator::prepare() {
    size_t bytes = size_t(num_pixels_) * kAccumBytesPerPixel;
    accum_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, bytes);
    dc_.queue.enqueueFillBuffer(accum_, cl_double(0), 0, bytes);
    image_buf_ = cl::Buffer(dc_.context, CL_MEM_WRITE_ONLY, size_t(num_pixels_) * kFilmBytesPerPixel);
    stats_.device_bytes = bytes + size_t(num_pixels_) * kFilmBytesPerPixel;
    stats_.hitpoints = num_pixels_;
}

void PtIntegrator::run_pass() {
    set_args(k_trace_, scene_.set_scene_args(k_trace_), scene_.camera_buf, cl_ulong(settings_.seed),
             cl_ulong(stats_.passes + 1), cl_uint(num_pixels_), accum_);
    cl::Event ev;
    enqueue_1d(dc_.queue, k_trace_, num_pixels_, &ev);
    add_event_time(stats_, "path_trace", ev);
    collect_event_times(stats_);
    stats_.passes += 1;
}

void PtIntegrator::save(Checkpoint& ck) {
    IntegratorBase::save(ck);
    ck.put("accum", read_buffer<cl_double>(dc_.queue, accum_, size_t(num_pixels_) * 3));
}

void PtIntegrator::restore(const Checkpoint& ck) {
    IntegratorBase::restore(ck);
    require_checkpoint_field(ck, stats_.photons_emitted == 0, "photons_emitted (a path tracer emits none)");
    std::vector<cl_double> accum = ck.get<cl_double>("accum", size_t(num_pixels_) * 3);
    check_radiance_sums(ck, accum, "accum");
    write_buffer(dc_.queue, accum_, accum);
}

Image PtIntegrator::image() {
    set_args(k_film_, 0, accum_, cl_uint(num_pixels_), cl_double(double(stats_.passes)), image_buf_);
    enqueue_1d(dc_.queue, k_film_, num_pixels_);
    return read_film(dc_, image_buf_, scene_.camera.width, scene_.camera.height);
}

} // namespace clppm
