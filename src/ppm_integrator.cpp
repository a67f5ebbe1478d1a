#include "ppm_integrator.h"

#include <algorithm>
#include <cmath>

#include "error.h"

namespace clppm {

namespace {

constexpr uint32_t kEyeSlots = 4;        // EYE_SLOTS for PPM (integrator_build_options)
constexpr uint32_t kEyeBatch = 1u << 18; // pixel samples per eye-pass launch
constexpr uint32_t kUpdateWg = 64;       // PPM_UPDATE_WG in kernels/ppm_update.cl

} // namespace

size_t radius_partials_bytes(uint32_t n) {
    return (std::max<uint32_t>(1, n) + kUpdateWg - 1) / kUpdateWg * sizeof(cl_float2);
}

std::pair<double, double> enqueue_ppm_update(const DeviceContext& dc, cl::Kernel& kernel, const cl::Buffer& passflux,
                                             const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                                             double alpha, const cl::Buffer& radius_partials, IntegratorStats& istats) {
    if (n == 0) return {0.0, 0.0};
    kernel.setArg(0, passflux);
    kernel.setArg(1, hitpoints);
    kernel.setArg(2, stats);
    kernel.setArg(3, cl_uint(n));
    kernel.setArg(4, cl_double(alpha));
    kernel.setArg(5, radius_partials);
    const size_t groups = (n + kUpdateWg - 1) / kUpdateWg;
    cl::Event ev;
    dc.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(groups * kUpdateWg), cl::NDRange(kUpdateWg),
                                  nullptr, &ev);
    std::vector<cl_float2> partials(groups);
    dc.queue.enqueueReadBuffer(radius_partials, CL_TRUE, 0, groups * sizeof(cl_float2), partials.data());
    add_event_time(istats, "update", ev);
    double sum = 0, mx = 0;
    for (const cl_float2& p : partials) sum += p.s[0], mx = std::max(mx, double(p.s[1]));
    return {sum / n, mx};
}

Image read_image(const DeviceContext& dc, const cl::Buffer& buffer, unsigned width, unsigned height) {
    std::vector<cl_float4> px(size_t(width) * height);
    dc.queue.enqueueReadBuffer(buffer, CL_TRUE, 0, px.size() * sizeof(cl_float4), px.data());
    Image img;
    img.width = int(width);
    img.height = int(height);
    img.rgb.resize(px.size() * 3);
    for (size_t i = 0; i < px.size(); ++i)
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = px[i].s[c];
    return img;
}

PpmIntegrator::PpmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                             const cl::Program& program, const SecondaryDevices& secondaries)
    : dc_(dc), scene_(scene), settings_(settings) {
    photons_ = std::make_unique<PhotonPasses>(dc, scene, settings_, program, stats_, secondaries.devices,
                                              secondaries.program_file, secondaries.build_options);
    photons_->set_hitpoints_fixed(true);
    k_eye_ = cl::Kernel(program, "eye_pass");
    k_direct_ = cl::Kernel(program, "direct_light");
    k_update_ = cl::Kernel(program, "ppm_update");
    k_film_ = cl::Kernel(program, "ppm_film");
    num_pixels_ = scene.camera.width * scene.camera.height;
}

void PpmIntegrator::prepare() { eye_pass(); }

// Sec. 4.1: hit points for every pixel sample, compacted on the host in pixel order so each
// pixel owns the range [pixel_first[p], pixel_first[p+1]).
void PpmIntegrator::eye_pass() {
    const uint64_t total_samples = uint64_t(num_pixels_) * settings_.spp;
    const uint32_t batch = uint32_t(std::min<uint64_t>(kEyeBatch, total_samples));
    cl::Buffer slots(dc_.context, CL_MEM_WRITE_ONLY, size_t(batch) * kEyeSlots * sizeof(dev::HitPoint));
    cl::Buffer sample_emission(dc_.context, CL_MEM_WRITE_ONLY, size_t(batch) * sizeof(cl_float4));
    std::vector<dev::HitPoint> host_slots(size_t(batch) * kEyeSlots);
    std::vector<cl_float4> host_emission(batch);

    std::vector<dev::HitPoint> hitpoints;
    std::vector<uint32_t> pixel_count(num_pixels_, 0);
    std::vector<cl_float4> emitted(num_pixels_, cl_float4{{0, 0, 0, 0}});
    int a = scene_.set_scene_args(k_eye_);
    k_eye_.setArg(a++, scene_.camera_buf);
    k_eye_.setArg(a++, cl_ulong(settings_.seed));
    k_eye_.setArg(a++, cl_ulong(0));
    const int first_arg = a;
    for (uint64_t first = 0; first < total_samples; first += batch) {
        uint32_t n = uint32_t(std::min<uint64_t>(batch, total_samples - first));
        a = first_arg;
        k_eye_.setArg(a++, cl_uint(first));
        k_eye_.setArg(a++, cl_uint(n));
        k_eye_.setArg(a++, cl_uint(settings_.spp));
        k_eye_.setArg(a++, slots);
        k_eye_.setArg(a++, sample_emission);
        cl::Event ev;
        enqueue_1d(dc_.queue, k_eye_, n, &ev);
        dc_.queue.enqueueReadBuffer(slots, CL_FALSE, 0, size_t(n) * kEyeSlots * sizeof(dev::HitPoint), host_slots.data());
        dc_.queue.enqueueReadBuffer(sample_emission, CL_TRUE, 0, size_t(n) * sizeof(cl_float4), host_emission.data());
        add_event_time(stats_, "eye_pass", ev);
        for (uint32_t i = 0; i < n; ++i) {
            uint32_t pixel = uint32_t((first + i) / settings_.spp);
            for (int c = 0; c < 3; ++c) emitted[pixel].s[c] += host_emission[i].s[c];
            for (uint32_t k = 0; k < kEyeSlots; ++k) {
                const dev::HitPoint& hp = host_slots[size_t(i) * kEyeSlots + k];
                if (hp.pixel == HITPOINT_NONE) continue;
                hitpoints.push_back(hp);
                ++pixel_count[pixel];
            }
        }
    }
    collect_event_times(stats_);
    std::vector<uint32_t> pixel_first(num_pixels_ + 1, 0);
    for (uint32_t p = 0; p < num_pixels_; ++p) pixel_first[p + 1] = pixel_first[p] + pixel_count[p];
    num_hitpoints_ = uint32_t(hitpoints.size());
    stats_.hitpoints = num_hitpoints_;

    std::vector<float> footprints;
    footprints.reserve(hitpoints.size());
    for (const dev::HitPoint& hp : hitpoints) footprints.push_back(hp.footprint);
    const double r0 = settings_.radius > 0 ? settings_.radius : initial_radius_heuristic(footprints, scene_.info.radius);
    stats_.initial_radius = stats_.mean_radius = r0;
    typical_radius_ = max_radius_ = r0;

    std::vector<dev::HitStats> hstats(std::max<size_t>(1, hitpoints.size()), dev::HitStats{r0 * r0, 0.0, {0, 0, 0}, {0, 0, 0}});
    if (hitpoints.empty()) hitpoints.resize(1); // buffers must not be empty; num_hitpoints_ stays 0
    auto make = [&](cl_mem_flags f, size_t bytes, const void* src) {
        stats_.device_bytes += bytes;
        return src ? cl::Buffer(dc_.context, f | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(src))
                   : cl::Buffer(dc_.context, f, bytes);
    };
    hitpoints_ = make(CL_MEM_READ_ONLY, hitpoints.size() * sizeof(dev::HitPoint), hitpoints.data());
    stats_buf_ = make(CL_MEM_READ_WRITE, hstats.size() * sizeof(dev::HitStats), hstats.data());
    passflux_ = make(CL_MEM_READ_WRITE, hstats.size() * sizeof(dev::PassFlux), nullptr);
    pixel_first_ = make(CL_MEM_READ_ONLY, pixel_first.size() * sizeof(uint32_t), pixel_first.data());
    emitted_ = make(CL_MEM_READ_ONLY, emitted.size() * sizeof(cl_float4), emitted.data());
    image_buf_ = make(CL_MEM_WRITE_ONLY, size_t(num_pixels_) * sizeof(cl_float4), nullptr);
    radius_partials_ = make(CL_MEM_WRITE_ONLY, radius_partials_bytes(num_hitpoints_), nullptr);
}

// Explicit direct light, then Eqs. 7-10 with this pass's M(x) and Phi_M(x).
void PpmIntegrator::update() {
    if (settings_.direct == DirectLighting::Sample)
        enqueue_direct_light(dc_, scene_, k_direct_, settings_.seed, stats_.passes + 1, hitpoints_, stats_buf_,
                             num_hitpoints_, stats_);
    auto [mean, mx] = enqueue_ppm_update(dc_, k_update_, passflux_, hitpoints_, stats_buf_, num_hitpoints_,
                                         settings_.alpha, radius_partials_, stats_);
    if (num_hitpoints_ > 0) stats_.mean_radius = typical_radius_ = mean, max_radius_ = mx;
}

void PpmIntegrator::run_pass() {
    photons_->run_pass(stats_.passes + 1, hitpoints_, stats_buf_, num_hitpoints_, 0.f, typical_radius_, max_radius_,
                       passflux_);
    update();
    collect_event_times(stats_);
    stats_.passes += 1;
    stats_.photons_emitted += settings_.photons;
}

// Hit points are part of the state too: on resume they must be the ones the statistics belong to.
void PpmIntegrator::save(Checkpoint& ck) {
    IntegratorBase::save(ck);
    const size_t n = std::max<size_t>(1, num_hitpoints_);
    ck.put("hitpoints", read_buffer<dev::HitPoint>(dc_.queue, hitpoints_, n));
    ck.put("stats", read_buffer<dev::HitStats>(dc_.queue, stats_buf_, n));
    ck.header["typical_radius"] = typical_radius_;
    ck.header["max_radius"] = max_radius_;
}

void PpmIntegrator::restore(const Checkpoint& ck) {
    IntegratorBase::restore(ck);
    const size_t n = std::max<size_t>(1, num_hitpoints_);
    write_buffer(dc_.queue, hitpoints_, ck.get<dev::HitPoint>("hitpoints", n));
    write_buffer(dc_.queue, stats_buf_, ck.get<dev::HitStats>("stats", n));
    typical_radius_ = ck.header.value("typical_radius", typical_radius_);
    max_radius_ = ck.header.value("max_radius", max_radius_);
}

Image PpmIntegrator::image() {
    k_film_.setArg(0, stats_buf_);
    k_film_.setArg(1, pixel_first_);
    k_film_.setArg(2, emitted_);
    k_film_.setArg(3, cl_uint(num_pixels_));
    k_film_.setArg(4, cl_uint(settings_.spp));
    k_film_.setArg(5, cl_double(scene_.info.total_power));
    k_film_.setArg(6, cl_double(double(stats_.photons_emitted)));
    k_film_.setArg(7, cl_double(double(settings_.direct == DirectLighting::Sample ? stats_.passes : 0)));
    k_film_.setArg(8, image_buf_);
    enqueue_1d(dc_.queue, k_film_, num_pixels_);
    return read_image(dc_, image_buf_, scene_.camera.width, scene_.camera.height);
}

} // namespace clppm
