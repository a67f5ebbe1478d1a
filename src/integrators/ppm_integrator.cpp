#include "integrators/ppm_integrator.h"

#include <algorithm>
#include <cmath>

#include "device/kernel_launch.h"
#include "integrators/film.h"
#include "integrators/initial_radius.h"
#include "integrators/progressive_update.h"
#include "util/error.h"

namespace clppm {

namespace {

constexpr uint32_t kEyeBatch = 1u << 18; // pixel samples per eye-pass launch
// Hit points per pixel sample that memory_needed allows for: a sample splits at glass and metal
// into up to PPM_EYE_SLOTS of them (measured ~1.1 in the Cornell box).
constexpr double kHitpointsPerSample = 1.25;

size_t eye_batch(size_t pixels, unsigned spp) { return std::min<size_t>(kEyeBatch, pixels * spp); }

} // namespace

IntegratorMemory PpmIntegrator::memory_needed(const RenderSettings& settings, size_t pixels, bool error_estimation) {
    const size_t hitpoints = size_t(kHitpointsPerSample * double(pixels) * settings.spp);
    const size_t per_hitpoint = sizeof(dev::HitPoint) + sizeof(dev::HitStats) + sizeof(dev::PassFlux);
    const size_t batch = eye_batch(pixels, settings.spp);
    IntegratorMemory m;
    m.bytes = hitpoints * per_hitpoint + radius_partials_bytes(uint32_t(std::min<size_t>(hitpoints, UINT32_MAX))) +
              (pixels + 1) * sizeof(uint32_t) + pixels * (sizeof(cl_float4) + kFilmBytesPerPixel) +
              batch * (PPM_EYE_SLOTS * sizeof(dev::HitPoint) + sizeof(cl_float4));
    m.largest_buffer = std::max(hitpoints * sizeof(dev::HitStats), batch * PPM_EYE_SLOTS * sizeof(dev::HitPoint));
    if (error_estimation) {
        // The Laplacian sums and sample indices per hit point; statistics, bounds and spread per
        // pixel; the seen emission per sample.
        m.bytes += hitpoints * (sizeof(cl_long) + sizeof(uint32_t)) +
                   pixels * (sizeof(dev::ErrorStats) + sizeof(cl_float8) + sizeof(float)) +
                   pixels * settings.spp * sizeof(float);
        m.largest_buffer = std::max(m.largest_buffer, pixels * sizeof(cl_float8));
    }
    return m;
}

PpmIntegrator::PpmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                             const cl::Program& program, const SecondaryDevices& secondaries)
    : PhotonMappingIntegrator(dc, scene, settings, program, secondaries) {
    photons_->set_hitpoints_fixed(true);
    volume_stats_ = true;
    k_film_ = cl::Kernel(program, "ppm_film");
}

void PpmIntegrator::prepare() {
    eye_pass();
    if (wants_errors_) make_error_estimator();
}

void PpmIntegrator::enable_error_estimation() {
    // The sample spread needs what the eye pass keeps only when asked.
    if (hitpoints_() && !errors_) throw Error("ppm: error estimation must be enabled before prepare()");
    wants_errors_ = true;
}

// The hit points exist only after the eye pass: it sizes the Laplacian sums.
void PpmIntegrator::make_error_estimator() {
    PixelHitpoints layout;
    layout.num_hitpoints = std::max<uint32_t>(1, num_hitpoints_);
    layout.pixel_first = pixel_first_;
    layout.emitted = emitted_;
    layout.spp = settings_.spp;
    errors_ = std::make_unique<ErrorEstimator>(dc_, program_, num_pixels_, stats_, layout);
    k_spread_ = cl::Kernel(program_, "error_sample_spread");
    photons_->set_second_gather(errors_->gather_kernel(), errors_->laplacian(), "error_estimate");
    errors_->reset(stats_buf_);
}

ErrorImage PpmIntegrator::error_estimate(double confidence) {
    if (!errors_) throw Error("error estimation is not enabled");
    set_args(k_spread_, 0, hitpoints_, stats_buf_, pixel_first_, hit_sample_, sample_y_, cl_uint(num_pixels_),
             cl_uint(settings_.spp), cl_double(scene_.info.total_power), cl_double(film_photons()),
             cl_double(double(settings_.direct == DirectLighting::Sample ? stats_.passes : 0)), spread_);
    enqueue_1d(dc_.queue, k_spread_, num_pixels_);
    const std::vector<float> spread = read_buffer<float>(dc_.queue, spread_, num_pixels_);
    return errors_->estimate(confidence, int(scene_.camera.width), int(scene_.camera.height), &spread,
                             normalization_variance());
}

// Sec. 4.1: hit points for every pixel sample, compacted on the host in pixel order so each
// pixel owns the range [pixel_first[p], pixel_first[p+1]).
void PpmIntegrator::eye_pass() {
    const uint64_t total_samples = uint64_t(num_pixels_) * settings_.spp;
    const uint32_t batch = uint32_t(eye_batch(num_pixels_, settings_.spp));
    cl::Buffer slots =
        make_buffer(dc_.context, CL_MEM_WRITE_ONLY, size_t(batch) * PPM_EYE_SLOTS * sizeof(dev::HitPoint));
    cl::Buffer sample_emission = make_buffer(dc_.context, CL_MEM_WRITE_ONLY, size_t(batch) * sizeof(cl_float4));
    stats_.device_bytes += size_t(batch) * (PPM_EYE_SLOTS * sizeof(dev::HitPoint) + sizeof(cl_float4));
    std::vector<dev::HitPoint> host_slots(size_t(batch) * PPM_EYE_SLOTS);
    std::vector<cl_float4> host_emission(batch);

    std::vector<dev::HitPoint> hitpoints;
    std::vector<uint32_t> pixel_count(num_pixels_, 0);
    // For the error estimate's sample spread: each hit point's sample within its pixel, and each
    // sample's seen emission (luminance).
    std::vector<uint32_t> hit_sample;
    std::vector<float> sample_y;
    std::vector<cl_float4> emitted(num_pixels_, cl_float4{{0, 0, 0, 0}});
    const int first_arg =
        set_args(k_eye_, scene_.set_scene_args(k_eye_), scene_.camera_buf, cl_ulong(settings_.seed), cl_ulong(0));
    for (uint64_t first = 0; first < total_samples; first += batch) {
        uint32_t n = uint32_t(std::min<uint64_t>(batch, total_samples - first));
        set_args(k_eye_, first_arg, cl_uint(first), cl_uint(n), cl_uint(settings_.spp), slots, sample_emission);
        cl::Event ev;
        enqueue_1d(dc_.queue, k_eye_, n, &ev);
        dc_.queue.enqueueReadBuffer(slots, CL_FALSE, 0, size_t(n) * PPM_EYE_SLOTS * sizeof(dev::HitPoint),
                                    host_slots.data());
        dc_.queue.enqueueReadBuffer(sample_emission, CL_TRUE, 0, size_t(n) * sizeof(cl_float4), host_emission.data());
        add_event_time(stats_, "eye_pass", ev);
        for (uint32_t i = 0; i < n; ++i) {
            uint32_t pixel = uint32_t((first + i) / settings_.spp);
            for (int c = 0; c < 3; ++c) emitted[pixel].s[c] += host_emission[i].s[c];
            if (wants_errors_) {
                const cl_float4& e = host_emission[i];
                sample_y.push_back(0.2126f * e.s[0] + 0.7152f * e.s[1] + 0.0722f * e.s[2]);
            }
            for (uint32_t k = 0; k < PPM_EYE_SLOTS; ++k) {
                const dev::HitPoint& hp = host_slots[size_t(i) * PPM_EYE_SLOTS + k];
                if (hp.pixel == HITPOINT_NONE) continue;
                hitpoints.push_back(hp);
                if (wants_errors_) hit_sample.push_back(uint32_t((first + i) % settings_.spp));
                ++pixel_count[pixel];
            }
        }
    }
    collect_event_times(stats_);
    std::vector<uint32_t> pixel_first(num_pixels_ + 1, 0);
    for (uint32_t p = 0; p < num_pixels_; ++p) pixel_first[p + 1] = pixel_first[p] + pixel_count[p];
    num_hitpoints_ = uint32_t(hitpoints.size());
    stats_.hitpoints = num_hitpoints_;
    hit_slots_ = std::max<uint32_t>(1, num_hitpoints_); // buffers are never empty

    // Surface and volume hit points (participating media) start from radii of their own, as
    // SPPM's do.
    const InitialRadii radii = initial_radii(hitpoints, settings_.radius, scene_.info.radius, scene_.media);
    const double r0 = radii.surface, rv = radii.volume;
    stats_.initial_volume_radius = rv;
    stats_.initial_radius = stats_.mean_radius = r0;
    typical_radius_ = max_radius_ = r0;

    std::vector<dev::HitStats> hstats(std::max<size_t>(1, hitpoints.size()),
                                      dev::HitStats{r0 * r0, 0.0, {0, 0, 0}, {0, 0, 0}});
    for (size_t k = 0; k < hitpoints.size(); ++k) {
        if (hitpoints[k].alpha >= 0) continue;
        hstats[k].r2 = rv * rv;
        max_radius_ = std::max(max_radius_, rv);
    }
    if (hitpoints.empty()) hitpoints.resize(1); // buffers must not be empty; num_hitpoints_ stays 0
    auto make = [&](cl_mem_flags f, size_t bytes, const void* src) {
        stats_.device_bytes += bytes;
        return src ? make_buffer(dc_.context, f | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(src))
                   : make_buffer(dc_.context, f, bytes);
    };
    hitpoints_ = make(CL_MEM_READ_ONLY, hitpoints.size() * sizeof(dev::HitPoint), hitpoints.data());
    stats_buf_ = make(CL_MEM_READ_WRITE, hstats.size() * sizeof(dev::HitStats), hstats.data());
    passflux_ = make(CL_MEM_READ_WRITE, hstats.size() * sizeof(dev::PassFlux), nullptr);
    pixel_first_ = make(CL_MEM_READ_ONLY, pixel_first.size() * sizeof(uint32_t), pixel_first.data());
    emitted_ = make(CL_MEM_READ_ONLY, emitted.size() * sizeof(cl_float4), emitted.data());
    image_buf_ = make(CL_MEM_WRITE_ONLY, size_t(num_pixels_) * kFilmBytesPerPixel, nullptr);
    radius_partials_ = make(CL_MEM_WRITE_ONLY, radius_partials_bytes(num_hitpoints_), nullptr);
    if (wants_errors_) {
        hit_sample.resize(hitpoints.size(), 0);
        hit_sample_ = make(CL_MEM_READ_ONLY, hit_sample.size() * sizeof(uint32_t), hit_sample.data());
        sample_y_ = make(CL_MEM_READ_ONLY, sample_y.size() * sizeof(float), sample_y.data());
        spread_ = make(CL_MEM_WRITE_ONLY, size_t(num_pixels_) * sizeof(float), nullptr);
    }
}

// Photons, explicit direct light, then Eqs. 7-10 with this pass's M(x) and Phi_M(x).
void PpmIntegrator::run_pass() {
    const uint64_t pass = stats_.passes + 1;
    photons_->run_pass(pass, hitpoints_, stats_buf_, num_hitpoints_, PassRadii{0.f, 0.f, typical_radius_, max_radius_},
                       passflux_);
    direct_light(pass, num_hitpoints_);
    progressive_update(num_hitpoints_);
    collect_event_times(stats_);
    stats_.passes = pass;
    stats_.photons_emitted += settings_.photons;
}

void PpmIntegrator::save_state(Checkpoint& ck) const {
    ck.put("hitpoints", read_buffer<dev::HitPoint>(dc_.queue, hitpoints_, hit_slots_));
}

void PpmIntegrator::restore_state(const Checkpoint& ck) {
    write_buffer(dc_.queue, hitpoints_, ck.get<dev::HitPoint>("hitpoints", hit_slots_));
}

Image PpmIntegrator::image() {
    set_args(k_film_, 0, hitpoints_, stats_buf_, pixel_first_, emitted_, cl_uint(num_pixels_), cl_uint(settings_.spp),
             cl_double(scene_.info.total_power), cl_double(film_photons()),
             cl_double(double(settings_.direct == DirectLighting::Sample ? stats_.passes : 0)), image_buf_);
    enqueue_1d(dc_.queue, k_film_, num_pixels_);
    return read_film(dc_, image_buf_, scene_.camera.width, scene_.camera.height);
}

} // namespace clppm
