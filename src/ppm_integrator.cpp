#include "ppm_integrator.h"

#include <algorithm>
#include <cmath>

#include "error.h"

namespace clppm {

namespace {

constexpr uint32_t kEyeSlots = 4;              // EYE_SLOTS in kernels/eye_pass.cl
constexpr uint32_t kEyeBatch = 1u << 18;       // pixel samples per eye-pass launch
constexpr uint32_t kUpdateWg = 64;             // PPM_UPDATE_WG in kernels/ppm_update.cl
constexpr uint32_t kScanWg = 256;              // GRID_SCAN_WG in kernels/hash_grid.cl

cl::NDRange global_for(size_t n, size_t wg = 1) { return cl::NDRange(std::max<size_t>(wg, (n + wg - 1) / wg * wg)); }

uint32_t next_pow2(uint32_t v) {
    uint32_t p = 1;
    while (p < v && p < (1u << 31)) p <<= 1;
    return p;
}

} // namespace

PpmIntegrator::PpmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                             const cl::Program& program)
    : dc_(dc), scene_(scene), settings_(settings) {
    k_eye_ = cl::Kernel(program, "eye_pass");
    k_photon_ = cl::Kernel(program, "photon_trace");
    k_count_ = cl::Kernel(program, "grid_count");
    k_scan_ = cl::Kernel(program, "grid_scan");
    k_scatter_ = cl::Kernel(program, "grid_scatter");
    k_gather_ = cl::Kernel(program, "gather");
    k_direct_ = cl::Kernel(program, "direct_light");
    k_update_ = cl::Kernel(program, "ppm_update");
    k_film_ = cl::Kernel(program, "ppm_film");
    num_pixels_ = scene.camera.width * scene.camera.height;
}

double PpmIntegrator::initial_radius(std::vector<float> footprints, double scene_radius) {
    double diameter = 2 * scene_radius;
    if (footprints.empty()) return 1e-3 * diameter;
    auto mid = footprints.begin() + footprints.size() / 2;
    std::nth_element(footprints.begin(), mid, footprints.end());
    double r = 2.0 * double(*mid);
    if (!std::isfinite(r)) r = 1e-3 * diameter;
    return std::clamp(r, 1e-6 * diameter, 0.05 * diameter);
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
    std::vector<uint32_t> pixel_first(num_pixels_ + 1, 0);
    for (uint32_t p = 0; p < num_pixels_; ++p) pixel_first[p + 1] = pixel_first[p] + pixel_count[p];
    num_hitpoints_ = uint32_t(hitpoints.size());
    stats_.hitpoints = num_hitpoints_;

    std::vector<float> footprints;
    footprints.reserve(hitpoints.size());
    for (const dev::HitPoint& hp : hitpoints) footprints.push_back(hp.footprint);
    double r0 = settings_.radius > 0 ? settings_.radius : initial_radius(footprints, scene_.info.radius);
    stats_.initial_radius = r0;
    stats_.mean_radius = r0;
    cell_radius_ = max_radius_ = r0;

    std::vector<dev::HitStats> hstats(std::max<size_t>(1, hitpoints.size()));
    for (dev::HitStats& s : hstats) s = dev::HitStats{r0 * r0, 0.0, {0, 0, 0}, {0, 0, 0}};
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
    size_t groups = (std::max<uint32_t>(1, num_hitpoints_) + kUpdateWg - 1) / kUpdateWg;
    radius_partials_ = make(CL_MEM_WRITE_ONLY, groups * sizeof(cl_float2), nullptr);
    counter_ = make(CL_MEM_READ_WRITE, sizeof(cl_uint), nullptr);
    grid_info_ = make(CL_MEM_READ_ONLY, sizeof(dev::GridInfo), nullptr);
}

// Sec. 4.2: M photons from the lights. Stored hits go to photons_; if they outgrow the buffer
// the pass is traced again into a larger one (same seed, so the same photons).
void PpmIntegrator::trace_photons() {
    const uint32_t M = uint32_t(settings_.photons);
    if (photon_capacity_ == 0)
        photon_capacity_ = uint32_t(std::clamp<uint64_t>(uint64_t(M) * 3, 1024, 0x7fffffffu));
    for (;;) {
        if (!photons_()) {
            photons_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, size_t(photon_capacity_) * sizeof(dev::Photon));
            sorted_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, size_t(photon_capacity_) * sizeof(dev::Photon));
        }
        dc_.queue.enqueueFillBuffer(counter_, cl_uint(0), 0, sizeof(cl_uint));
        int a = scene_.set_scene_args(k_photon_);
        k_photon_.setArg(a++, cl_ulong(settings_.seed));
        k_photon_.setArg(a++, cl_ulong(stats_.passes + 1));
        k_photon_.setArg(a++, cl_uint(0));
        k_photon_.setArg(a++, cl_uint(M));
        k_photon_.setArg(a++, cl_uint(settings_.direct == DirectLighting::Sample ? 1 : 0));
        k_photon_.setArg(a++, photons_);
        k_photon_.setArg(a++, cl_uint(photon_capacity_));
        k_photon_.setArg(a++, counter_);
        cl::Event ev;
        enqueue_1d(dc_.queue, k_photon_, M, &ev);
        cl_uint stored = 0;
        dc_.queue.enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_uint), &stored);
        add_event_time(stats_, "photon_trace", ev);
        if (stored <= photon_capacity_) {
            photons_this_pass_ = stored;
            return;
        }
        photon_capacity_ = uint32_t(std::min<uint64_t>(uint64_t(stored) * 5 / 4 + 1024, 0x7fffffffu));
        photons_ = cl::Buffer();
    }
}

// Sec. 4.3: the hashed grid of this pass's photons. Cells are sized for the hit points' radii:
// twice the mean radius, but no smaller than a quarter of the largest so that no hit point
// visits more than 9^3 cells, and no finer than 2^-20 of the scene.
void PpmIntegrator::build_grid() {
    const uint32_t n = photons_this_pass_;
    dev::GridInfo g{};
    double extent = 2.0 * scene_.info.radius;
    double cell = std::max({2.0 * cell_radius_, max_radius_ / 4.0, extent / double(1 << 20)});
    for (int k = 0; k < 3; ++k) g.origin[k] = scene_.bounds_min[k];
    g.inv_cell = float(1.0 / cell);
    g.num_photons = n;
    uint32_t table = next_pow2(std::max<uint32_t>(1024, n));
    g.table_size = table;
    if (table != table_size_) {
        counts_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, size_t(table) * sizeof(cl_uint));
        starts_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, size_t(table + 1) * sizeof(cl_uint));
        table_size_ = table;
    }
    dc_.queue.enqueueWriteBuffer(grid_info_, CL_FALSE, 0, sizeof g, &g);
    dc_.queue.enqueueFillBuffer(counts_, cl_uint(0), 0, size_t(table) * sizeof(cl_uint));
    cl::Event e1, e2, e3;
    k_count_.setArg(0, grid_info_);
    k_count_.setArg(1, photons_);
    k_count_.setArg(2, counts_);
    enqueue_1d(dc_.queue, k_count_, n, &e1);
    k_scan_.setArg(0, counts_);
    k_scan_.setArg(1, starts_);
    k_scan_.setArg(2, cl_uint(table));
    dc_.queue.enqueueNDRangeKernel(k_scan_, cl::NullRange, cl::NDRange(kScanWg), cl::NDRange(kScanWg), nullptr, &e2);
    k_scatter_.setArg(0, grid_info_);
    k_scatter_.setArg(1, photons_);
    k_scatter_.setArg(2, starts_);
    k_scatter_.setArg(3, counts_);
    k_scatter_.setArg(4, sorted_);
    enqueue_1d(dc_.queue, k_scatter_, n, &e3);
    e3.wait();
    add_event_time(stats_, "grid_build", e1);
    add_event_time(stats_, "grid_build", e2);
    add_event_time(stats_, "grid_build", e3);
}

void PpmIntegrator::gather_and_update() {
    const uint32_t n = num_hitpoints_;
    if (n == 0) return;
    cl::Event eg, ed, eu;
    k_gather_.setArg(0, grid_info_);
    k_gather_.setArg(1, sorted_);
    k_gather_.setArg(2, starts_);
    k_gather_.setArg(3, hitpoints_);
    k_gather_.setArg(4, stats_buf_);
    k_gather_.setArg(5, cl_uint(n));
    k_gather_.setArg(6, passflux_);
    enqueue_1d(dc_.queue, k_gather_, n, &eg);
    if (settings_.direct == DirectLighting::Sample) {
        int a = scene_.set_scene_args(k_direct_);
        k_direct_.setArg(a++, cl_ulong(settings_.seed));
        k_direct_.setArg(a++, cl_ulong(stats_.passes + 1));
        k_direct_.setArg(a++, hitpoints_);
        k_direct_.setArg(a++, stats_buf_);
        k_direct_.setArg(a++, cl_uint(n));
        enqueue_1d(dc_.queue, k_direct_, n, &ed);
    }
    k_update_.setArg(0, passflux_);
    k_update_.setArg(1, hitpoints_);
    k_update_.setArg(2, stats_buf_);
    k_update_.setArg(3, cl_uint(n));
    k_update_.setArg(4, cl_double(settings_.alpha));
    k_update_.setArg(5, radius_partials_);
    dc_.queue.enqueueNDRangeKernel(k_update_, cl::NullRange, global_for(n, kUpdateWg), cl::NDRange(kUpdateWg), nullptr,
                                   &eu);
    size_t groups = (n + kUpdateWg - 1) / kUpdateWg;
    std::vector<cl_float2> partials(groups);
    dc_.queue.enqueueReadBuffer(radius_partials_, CL_TRUE, 0, groups * sizeof(cl_float2), partials.data());
    add_event_time(stats_, "gather", eg);
    if (settings_.direct == DirectLighting::Sample) add_event_time(stats_, "direct_light", ed);
    add_event_time(stats_, "update", eu);
    double sum = 0, mx = 0;
    for (const cl_float2& p : partials) sum += p.s[0], mx = std::max(mx, double(p.s[1]));
    stats_.mean_radius = sum / n;
    cell_radius_ = stats_.mean_radius;
    max_radius_ = mx;
}

void PpmIntegrator::run_pass() {
    trace_photons();
    build_grid();
    gather_and_update();
    stats_.passes += 1;
    stats_.photons_emitted += settings_.photons;
    stats_.photons_stored += photons_this_pass_;
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
    std::vector<cl_float4> px(num_pixels_);
    dc_.queue.enqueueReadBuffer(image_buf_, CL_TRUE, 0, px.size() * sizeof(cl_float4), px.data());
    Image img;
    img.width = int(scene_.camera.width);
    img.height = int(scene_.camera.height);
    img.rgb.resize(size_t(num_pixels_) * 3);
    for (size_t i = 0; i < px.size(); ++i)
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = px[i].s[c];
    return img;
}

} // namespace clppm
