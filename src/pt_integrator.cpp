#include "pt_integrator.h"

#include "ppm_integrator.h"

namespace clppm {

PtIntegrator::PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                           const cl::Program& program)
    : dc_(dc), scene_(scene), settings_(settings) {
    k_trace_ = cl::Kernel(program, "path_trace");
    k_film_ = cl::Kernel(program, "pt_film");
    num_pixels_ = scene.camera.width * scene.camera.height;
}

void PtIntegrator::prepare() {
    size_t bytes = size_t(num_pixels_) * 3 * sizeof(cl_double);
    accum_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, bytes);
    dc_.queue.enqueueFillBuffer(accum_, cl_double(0), 0, bytes);
    image_buf_ = cl::Buffer(dc_.context, CL_MEM_WRITE_ONLY, size_t(num_pixels_) * sizeof(cl_float4));
    stats_.device_bytes = bytes + size_t(num_pixels_) * sizeof(cl_float4);
    stats_.hitpoints = num_pixels_;
}

void PtIntegrator::run_pass() {
    int a = scene_.set_scene_args(k_trace_);
    k_trace_.setArg(a++, scene_.camera_buf);
    k_trace_.setArg(a++, cl_ulong(settings_.seed));
    k_trace_.setArg(a++, cl_ulong(stats_.passes + 1));
    k_trace_.setArg(a++, cl_uint(num_pixels_));
    k_trace_.setArg(a++, accum_);
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
    write_buffer(dc_.queue, accum_, ck.get<cl_double>("accum", size_t(num_pixels_) * 3));
}

Image PtIntegrator::image() {
    k_film_.setArg(0, accum_);
    k_film_.setArg(1, cl_uint(num_pixels_));
    k_film_.setArg(2, cl_double(double(stats_.passes)));
    k_film_.setArg(3, image_buf_);
    enqueue_1d(dc_.queue, k_film_, num_pixels_);
    return read_image(dc_, image_buf_, scene_.camera.width, scene_.camera.height);
}

} // namespace clppm
