#include "integrators/vcm_integrator.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "device/kernel_launch.h"
#include "device/kernel_program.h"
#include "integrators/checkpoint_checks.h"
#include "integrators/film.h"
#include "integrators/initial_radius.h"
#include "integrators/integrator_table.h"
#include "integrators/progressive_update.h"
#include "util/cancellation.h"
#include "util/error.h"

namespace clppm {

namespace {

// Per pixel: the running sum, this pass's sum over batches, the fixed-point splat image (3 double
// or int64 each), the film, and the light sub-path's last vertex.
constexpr size_t kBytesPerPixel =
    3 * sizeof(cl_double) * 2 + 3 * sizeof(cl_long) + kFilmBytesPerPixel + sizeof(cl_uint);
// Light vertices a buffer starts out sized for per light sub-path; it grows if a scene stores more.
constexpr uint64_t kVerticesPerPath = 4;
// The splat image's fixed point (light tracing, t = 1): exact sums in any order.
constexpr double kSplatScale = 4294967296.0; // 2^32

uint32_t technique_mode(const RenderSettings& s) {
    if (s.vcm_techniques >= 0) return uint32_t(s.vcm_techniques);
    return integrator_row(s.integrator).mode;
}

} // namespace

IntegratorMemory VcmIntegrator::memory_needed(size_t pixels, bool error_estimation) {
    const IntegratorMemory m{pixels * kBytesPerPixel, pixels * 3 * sizeof(cl_double)};
    return error_estimation ? with_error_estimation(m, pixels) : m;
}

size_t VcmIntegrator::light_vertex_bytes(size_t pixels, const DeviceInfo& device) {
    const uint64_t capacity =
        BatchedTrace::initial_capacity(pixels, kVerticesPerPath, sizeof(dev::LightVertex), device);
    return 2 * size_t(capacity) * sizeof(dev::LightVertex) + HashGrid::bytes_for(capacity);
}

// A further device: its own context, copy of the scene and program, and an integrator of its own
// whose running sum holds one pass at a time.
struct VcmIntegrator::Worker {
    DeviceContext dc;
    DeviceScene scene;
    cl::Program program;
    std::unique_ptr<VcmIntegrator> integ;
    std::vector<double> result; // its pixels' samples this pass

    Worker(const DeviceInfo& info, const DeviceContext& primary, const DeviceScene& primary_scene,
           const RenderSettings& settings, const std::string& file, const std::string& options)
        : dc(info), scene(primary_scene.clone_to(primary, dc)), program(build_program(dc, file, options)) {
        integ = std::make_unique<VcmIntegrator>(dc, scene, settings, program);
    }
};

VcmIntegrator::VcmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                             const cl::Program& program, const SecondaryDevices& secondaries)
    : PixelSumIntegrator(dc, scene, settings, program), mode_(technique_mode(settings)), grid_(dc, program, stats_) {
    // Light sub-paths reach the camera through its importance, which is written for a pinhole or
    // a thin lens (kernels/vcm.cl); an orthographic camera has neither.
    if (scene.camera.forward[3] != 0.f && mode_ != VCM_MODE_PT)
        throw Error("--integrator: vcm, bpt and lt need a perspective camera; the scene's is orthographic (pt, "
                    "sppm, pppm and ppm render it)");
    k_light_ = cl::Kernel(program, "vcm_light");
    k_camera_ = cl::Kernel(program, "vcm_camera");
    k_footprint_ = cl::Kernel(program, "vcm_footprint");
    area_scale_ = std::min(double(scene.info.radius) * double(scene.info.radius), double(FLT_MAX));
    trace_ = std::make_unique<BatchedTrace>(dc, sizeof(dev::LightVertex), kVerticesPerPath,
                                            std::max<uint32_t>(1, num_pixels_), "one light sub-path", "vertices");
    std::vector<unsigned> compute_units{dc.info.compute_units};
    for (const DeviceInfo& info : secondaries.devices) {
        workers_.push_back(
            std::make_unique<Worker>(info, dc, scene, settings, secondaries.program_file, secondaries.build_options));
        compute_units.push_back(info.compute_units);
    }
    fan_out_ = DeviceFanOut(compute_units);
}

VcmIntegrator::~VcmIntegrator() {
    try {
        dc_.queue.finish(); // non-blocking writes may still read host memory
    } catch (const cl::Error&) {}
}

double VcmIntegrator::radius() const { return std::sqrt(r2_); }

void VcmIntegrator::prepare() {
    const size_t n = num_pixels_;
    auto make = [&](size_t bytes) {
        stats_.device_bytes += bytes;
        return make_buffer(dc_.context, CL_MEM_READ_WRITE, std::max<size_t>(bytes, 8));
    };
    allocate_sum();
    pass_sum_ = make(n * 3 * sizeof(cl_double));
    splat_ = make(n * 3 * sizeof(cl_long));
    path_last_ = make(size_t(trace_->batch()) * sizeof(cl_uint));

    // The initial merging radius: one pixel footprint at the first surfaces, half of SPPM's two.
    // Merging takes most of the weight on diffuse surfaces (eta = pi r^2 N_L is large), so its
    // bias is the image's: on the diffuse box at 48x48, 256 passes, SPPM's radius (0.126) left the
    // mean 1.7% low and r = 0.05 0.1% (tests/vcm_test.cpp).
    cl::Buffer fp = make_buffer(dc_.context, CL_MEM_WRITE_ONLY, std::max<size_t>(n, 1) * sizeof(cl_float));
    set_args(k_footprint_, scene_.set_scene_args(k_footprint_), scene_.camera_buf, cl_uint(num_pixels_), fp);
    enqueue_1d(dc_.queue, k_footprint_, n);
    std::vector<float> all = read_buffer<cl_float>(dc_.queue, fp, n), footprints;
    for (float f : all)
        if (f > 0) footprints.push_back(f);
    const double r0 =
        settings_.radius > 0 ? settings_.radius : 0.5 * initial_radius_heuristic(footprints, scene_.info.radius);
    stats_.initial_radius = stats_.mean_radius = r0;
    r2_ = r0 * r0;
    for (auto& w : workers_) w->integ->prepare(); // their radius is set from this one's every pass
}

// What both sub-path kernels are told this pass (dev::VcmPass): the MIS factors from the merging
// radius, eta = pi r^2 N_L in scene-relative area (Georgiev et al. 2012), and the units of the
// light-side sums.
dev::VcmPass VcmIntegrator::pass_constants(uint64_t pass) const {
    const double eta = M_PI * r2_ / area_scale_ * double(num_pixels_);
    const bool vm = mode_ == VCM_MODE_VCM || mode_ == VCM_MODE_VM;
    dev::VcmPass p{};
    p.seed = settings_.seed;
    p.pass = pass;
    // Light-side sums are in units of total power per scene-relative area (kernels/vcm.cl).
    p.light_unit = double(scene_.info.total_power) / area_scale_;
    p.vm_norm = area_scale_ / (M_PI * r2_ * double(num_pixels_));
    p.splat_unit = p.light_unit / kSplatScale;
    p.light_paths = float(num_pixels_);
    p.vm_factor = vm ? float(std::min(eta * eta, 1e30)) : 0.f;
    p.vc_factor = mode_ == VCM_MODE_VCM ? float(std::min(1.0 / (eta * eta), 1e30)) : 0.f;
    p.area_scale = float(area_scale_);
    p.r2 = float(r2_);
    p.splat_scale = float(kSplatScale);
    p.mode = mode_;
    p.max_len = scene_.info.max_bounces + 1;
    return p;
}

void VcmIntegrator::trace_light(const dev::VcmPass& vp, uint32_t first, uint32_t count) {
    fill_buffer(dc_.queue, splat_, cl_long(0), 0, size_t(num_pixels_) * 3 * sizeof(cl_long));
    if (mode_ == VCM_MODE_PT) return; // camera sub-paths alone
    set_args(k_light_, scene_.set_scene_args(k_light_), scene_.camera_buf, vp, cl_uint(first), cl_uint(count),
             trace_->records(), cl_uint(trace_->capacity()), trace_->counter(), path_last_, splat_);
    cl::Event ev;
    enqueue_1d(dc_.queue, k_light_, count, &ev);
    add_event_time(stats_, "light_paths", ev);
}

void VcmIntegrator::render(uint64_t pass, uint32_t first_pixel, uint32_t pixels, const cl::Buffer& out) {
    const dev::VcmPass vp = pass_constants(pass);
    const bool vm = mode_ == VCM_MODE_VCM || mode_ == VCM_MODE_VM;
    const double extent = 2.0 * scene_.info.radius;
    const double cell = std::max(2.0 * std::sqrt(r2_), extent / double(1 << 20));
    uint64_t stored_total = 0;
    trace_->run(
        0, num_pixels_, [&](uint32_t first, uint32_t count) { trace_light(vp, first, count); },
        [&](uint32_t first, uint32_t count, uint32_t stored) {
            grid_.build(trace_->records(), trace_->sorted(), vm ? stored : 0, scene_.bounds_min,
                        cell); // an empty grid without merging
            const uint32_t flags = (first == 0 ? 1u : 0u) | (first + count == num_pixels_ ? 2u : 0u);
            set_args(k_camera_, scene_.set_scene_args(k_camera_), scene_.camera_buf, vp, cl_uint(first_pixel + pixels),
                     grid_.info(), trace_->sorted(), grid_.starts(), trace_->records(), path_last_, cl_uint(first),
                     cl_uint(count), cl_uint(flags), splat_, pass_sum_, out);
            if (pixels > 0) {
                cl::Event ev;
                enqueue_1d_range(dc_.queue, k_camera_, first_pixel, pixels, &ev);
                add_event_time(stats_, "camera_paths", ev);
            }
            stored_total += stored;
        });
    collect_event_times(stats_); // waits for the pass
    stats_.photons_stored += stored_total;
    stats_.photon_bytes = trace_->device_bytes() + grid_.device_bytes();
}

// With several processes (device/cluster.h) every rank traces all light sub-paths (the same on
// each: they depend on (seed, pass, index) alone) and the camera sub-paths of its own pixel range,
// by the ranks' measured speed; the ranks then share their ranges of the running sum, so each holds
// what one process would, bit for bit when their batches agree. Several devices in one process
// share the rank's range the same way.
void VcmIntegrator::run_pass() {
    const uint64_t pass = stats_.passes + 1;
    const PixelRanges ranges = begin_pass();
    if (workers_.empty()) render(pass, ranges.first, ranges.count, accum_);
    else render_on_devices(pass, ranges);
    end_pass(ranges);
    stats_.photons_emitted += mode_ == VCM_MODE_PT ? 0 : num_pixels_;
    stats_.mean_radius = std::sqrt(r2_);
    r2_ = next_pppm_radius2(r2_, pass, settings_.alpha);
}

// The rank's range in proportion to each device's pixels per second, the primary first; each
// device's samples join the running sum as its own kernel would have added them.
void VcmIntegrator::render_on_devices(uint64_t pass, const PixelRanges& ranges) {
    const std::vector<uint32_t> share = fan_out_.split(ranges.count);
    fan_out_.run(ranges.first, share, [&](size_t k, uint32_t first, uint32_t count) {
        if (k == 0) return render(pass, first, count, accum_);
        Worker& w = *workers_[k - 1];
        VcmIntegrator& v = *w.integ;
        v.r2_ = r2_;
        const size_t bytes = size_t(num_pixels_) * 3 * sizeof(cl_double);
        fill_buffer(v.dc_.queue, v.accum_, cl_double(0), 0, bytes); // this pass alone
        v.render(pass, first, count, v.accum_);
        w.result.assign(size_t(count) * 3, 0.0);
        if (count)
            v.dc_.queue.enqueueReadBuffer(v.accum_, CL_TRUE, size_t(first) * 3 * sizeof(cl_double),
                                          w.result.size() * sizeof(double), w.result.data());
    });
    uint32_t at = ranges.first + share[0];
    for (size_t k = 0; k < workers_.size(); ++k) {
        const uint32_t count = share[k + 1];
        if (count) {
            std::vector<double> sum(size_t(count) * 3);
            const size_t offset = size_t(at) * 3 * sizeof(cl_double);
            dc_.queue.enqueueReadBuffer(accum_, CL_TRUE, offset, sum.size() * sizeof(double), sum.data());
            for (size_t i = 0; i < sum.size(); ++i) sum[i] += workers_[k]->result[i];
            write_bytes(dc_.queue, accum_, offset, sum.size() * sizeof(double), sum.data());
        }
        at += count;
    }
    stats_.device_photons = share;
}

void VcmIntegrator::save(Checkpoint& ck) {
    IntegratorBase::save(ck);
    save_sum(ck);
    ck.header["vcm_r2"] = r2_;
}

void VcmIntegrator::restore(const Checkpoint& ck) {
    IntegratorBase::restore(ck);
    const uint64_t per_pass = mode_ == VCM_MODE_PT ? 0 : num_pixels_;
    require_checkpoint_field(ck, stats_.photons_emitted == stats_.passes * per_pass,
                             "photons_emitted (one light sub-path per pixel and pass)");
    const double r0 = stats_.initial_radius;
    require_checkpoint_field(ck, std::isfinite(r0) && r0 > 0 && r0 <= 2.0 * scene_.info.radius, "initial_radius");
    r2_ = checkpoint_number(ck, "vcm_r2", 0, r0 * r0 * (1 + 1e-9));
    require_checkpoint_field(ck, r2_ > 0, "vcm_r2");
    restore_sum(ck);
}

} // namespace clppm
