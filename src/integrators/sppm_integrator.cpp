#include "integrators/sppm_integrator.h"

#include <cmath>

#include "device/kernel_launch.h"
#include "integrators/checkpoint_checks.h"
#include "integrators/film.h"
#include "integrators/initial_radius.h"
#include "integrators/integrator_table.h"
#include "integrators/progressive_update.h"
#include "util/error.h"

namespace clppm {

SppmIntegrator::SppmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                               const cl::Program& program, const SecondaryDevices& secondaries)
    : PhotonMappingIntegrator(dc, scene, settings, program, secondaries),
      probabilistic_(integrator_row(settings.integrator).mode == kProbabilisticRadii) {
    k_emission_ = cl::Kernel(program, "accumulate_emission");
    k_accumulate_ = cl::Kernel(program, "pppm_accumulate");
    k_film_ = cl::Kernel(program, probabilistic_ ? "pppm_film" : "sppm_film");
    if (scene.media) k_volume_ = cl::Kernel(program, "volume_accumulate");
    beams_ = scene.media && settings.volume_gather == VolumeGather::Beams;
    eye_args_ = k_eye_.getInfo<CL_KERNEL_NUM_ARGS>();
    if (beams_) {
        k_beam_accumulate_ = cl::Kernel(program, "beam_accumulate");
        k_beam_direct_ = cl::Kernel(program, "beam_direct_light");
    }
}

IntegratorMemory SppmIntegrator::memory_needed(size_t pixels, bool error_estimation, bool beams) {
    // Visible point, seen emission, statistics, pass flux and film per pixel, the radius partials;
    // with beams (--volume-gather beams in a scene with media) a second slot of the first three per
    // pixel, as prepare() makes them (counted whenever beams are asked for: a scene without media
    // is then over-estimated, never under).
    const size_t slots = beams ? 2 * pixels : pixels;
    IntegratorMemory m;
    m.bytes = slots * (sizeof(dev::HitPoint) + sizeof(dev::HitStats) + sizeof(dev::PassFlux)) +
              pixels * (sizeof(cl_float4) + kFilmBytesPerPixel) + radius_partials_bytes(uint32_t(pixels));
    m.largest_buffer = slots * std::max(sizeof(dev::HitPoint), sizeof(dev::HitStats));
    if (error_estimation) {
        m.bytes += ErrorEstimator::bytes_per_pixel() * pixels;
        m.largest_buffer = std::max(m.largest_buffer, pixels * sizeof(dev::ErrorStats));
    }
    return m;
}

void SppmIntegrator::prepare() {
    const size_t n = num_pixels_;
    slots_ = beams_ ? 2 * num_pixels_ : num_pixels_;
    auto make = [&](size_t bytes) {
        stats_.device_bytes += bytes;
        return make_buffer(dc_.context, CL_MEM_READ_WRITE, bytes);
    };
    hitpoints_ = make(slots_ * sizeof(dev::HitPoint));
    sample_emission_ = make(n * sizeof(cl_float4));
    stats_buf_ = make(slots_ * sizeof(dev::HitStats));
    passflux_ = make(slots_ * sizeof(dev::PassFlux));
    image_buf_ = make(n * kFilmBytesPerPixel);
    radius_partials_ = make(radius_partials_bytes(num_pixels_));
    stats_.hitpoints = n;
    hit_slots_ = num_pixels_;

    // The first pass's visible points decide the initial radius, as PPM's hit points do.
    eye_pass(1);
    std::vector<dev::HitPoint> hps(slots_);
    dc_.queue.enqueueReadBuffer(hitpoints_, CL_TRUE, 0, slots_ * sizeof(dev::HitPoint), hps.data());
    const InitialRadii radii = initial_radii(hps, settings_.radius, scene_.info.radius, scene_.media);
    const double r0 = radii.surface;
    volume_r0_ = stats_.initial_volume_radius = radii.volume;
    stats_.initial_radius = stats_.mean_radius = typical_radius_ = max_radius_ = r0;
    r2_ = r0 * r0;
    const dev::HitStats init{r0 * r0, 0.0, {0, 0, 0}, {0, 0, 0}};
    fill_buffer(dc_.queue, stats_buf_, init, 0, slots_ * sizeof(dev::HitStats));
    if (errors_) errors_->reset(stats_buf_);
}

void SppmIntegrator::enable_error_estimation() {
    if (errors_) return;
    PixelHitpoints layout;
    layout.num_hitpoints = slots_; // the second gather writes every slot; a beam's is 0
    errors_ = std::make_unique<ErrorEstimator>(dc_, program_, num_pixels_, stats_, layout);
    photons_->set_second_gather(errors_->gather_kernel(), errors_->laplacian(), "error_estimate");
    if (stats_buf_()) errors_->reset(stats_buf_); // after prepare(): the estimate starts here
}

// New visible points for every pixel; their seen emission joins the per-pixel running sum.
void SppmIntegrator::eye_pass(uint64_t pass) {
    const int a = set_args(k_eye_, scene_.set_scene_args(k_eye_), scene_.camera_buf, cl_ulong(settings_.seed),
                           cl_ulong(pass), cl_uint(0), cl_uint(num_pixels_), cl_uint(1), hitpoints_, sample_emission_);
    // A program with media takes whether the buffer has the beams' slots (kernels/eye_pass.cl EYE_BEAMS).
    if (eye_args_ > cl_uint(a)) k_eye_.setArg(a, cl_uint(beams_ ? 1 : 0));
    cl::Event ev;
    enqueue_1d(dc_.queue, k_eye_, num_pixels_, &ev);
    add_event_time(stats_, "eye_pass", ev);
}

void SppmIntegrator::run_pass() {
    const uint64_t pass = stats_.passes + 1;
    if (pass > 1) eye_pass(pass);
    // The photons first: a pass cancelled between photon batches (Ctrl-C) leaves the statistics
    // as the last complete pass left them. The gather reads only their radii, which the emission
    // and direct light below do not touch, so the order changes no result.
    PassRadii radii;
    if (probabilistic_) {
        const double r = std::sqrt(r2_);
        radii = PassRadii{float(r2_), 0.f, r, r};
    } else {
        radii = PassRadii{0.f, 0.f, typical_radius_, max_radius_};
    }
    if (scene_.media) {
        const double rv = volume_radius();
        radii.volume_r2 = float(rv * rv);
        radii.max = std::max(radii.max, rv);
        if (beams_) radii.beam_r2 = float(beam_radius() * beam_radius());
    }
    photons_->run_pass(pass, hitpoints_, stats_buf_, slots_, radii, passflux_);
    set_args(k_emission_, 0, sample_emission_, stats_buf_, cl_uint(num_pixels_));
    enqueue_1d(dc_.queue, k_emission_, num_pixels_);
    direct_light(pass, num_pixels_);
    if (scene_.media) volume_update(pass);
    if (probabilistic_) probabilistic_update();
    else progressive_update(num_pixels_);
    collect_event_times(stats_);
    stats_.passes = pass;
    stats_.photons_emitted += settings_.photons;
}

double SppmIntegrator::volume_radius() const { return volume_r0_ * std::cbrt(volume_shrink_); }

double SppmIntegrator::beam_radius() const { return kBeamRadiusScale * volume_r0_ * std::sqrt(volume_shrink_); }

// Before the error estimate's update, which reads the pixels' direct sums.
void SppmIntegrator::volume_update(uint64_t pass) {
    const double rv = volume_radius();
    const double scale = power_per_photon() / (4.0 / 3.0 * M_PI * rv * rv * rv);
    set_args(k_volume_, 0, passflux_, hitpoints_, stats_buf_, cl_uint(num_pixels_), cl_double(scale));
    cl::Event ev;
    enqueue_1d(dc_.queue, k_volume_, num_pixels_, &ev);
    add_event_time(stats_, "volume", ev);
    if (beams_) {
        const double rb = beam_radius();
        set_args(k_beam_accumulate_, 0, passflux_, hitpoints_, stats_buf_, cl_uint(num_pixels_),
                 cl_double(power_per_photon() / (M_PI * rb * rb)));
        enqueue_1d(dc_.queue, k_beam_accumulate_, num_pixels_, &ev);
        add_event_time(stats_, "volume", ev);
        if (settings_.direct == DirectLighting::Sample) {
            set_args(k_beam_direct_, scene_.set_scene_args(k_beam_direct_), cl_ulong(settings_.seed), cl_ulong(pass),
                     hitpoints_, stats_buf_, cl_uint(num_pixels_));
            enqueue_1d(dc_.queue, k_beam_direct_, num_pixels_, &ev);
            add_event_time(stats_, "direct_light", ev);
        }
    }
    volume_shrink_ = next_pppm_radius2(volume_shrink_, pass, settings_.alpha);
    stats_.volume_radius = volume_radius();
}

// Knaus and Zwicker 2011: each pass's estimate with this pass's radius joins a running mean; the
// radius then shrinks for every pixel alike (Eq. 20).
void SppmIntegrator::probabilistic_update() {
    if (errors_) errors_->update(passflux_, hitpoints_, stats_buf_, r2_, power_per_photon());
    set_args(k_accumulate_, 0, passflux_, hitpoints_, stats_buf_, cl_uint(num_pixels_), cl_double(1.0 / (M_PI * r2_)));
    cl::Event ev;
    enqueue_1d(dc_.queue, k_accumulate_, num_pixels_, &ev);
    add_event_time(stats_, "update", ev);
    dc_.queue.finish();
    r2_ = next_pppm_radius2(r2_, stats_.passes + 1, settings_.alpha);
    stats_.mean_radius = std::sqrt(r2_);
}

void SppmIntegrator::save_state(Checkpoint& ck) const {
    ck.header["pppm_r2"] = r2_;
    ck.header["volume_r0"] = volume_r0_;
    ck.header["volume_shrink"] = volume_shrink_;
}

void SppmIntegrator::restore_state(const Checkpoint& ck) {
    const double r0 = stats_.initial_radius;
    r2_ = checkpoint_number(ck, "pppm_r2", 0, r0 * r0 * (1 + 1e-9));
    require_checkpoint_field(ck, r2_ > 0, "pppm_r2");
    if (!scene_.media) return;
    volume_r0_ = checkpoint_number(ck, "volume_r0", 0, 2 * scene_.info.radius);
    volume_shrink_ = checkpoint_number(ck, "volume_shrink", 0, 1);
    require_checkpoint_field(ck, volume_r0_ > 0 && volume_shrink_ > 0, "volume_r0");
    stats_.initial_volume_radius = volume_r0_;
    stats_.volume_radius = volume_radius();
}

Image SppmIntegrator::image() {
    int a = set_args(k_film_, 0, stats_buf_, cl_uint(num_pixels_));
    if (probabilistic_) a = set_args(k_film_, a, cl_double(power_per_photon()));
    else a = set_args(k_film_, a, cl_double(scene_.info.total_power), cl_double(film_photons()));
    set_args(k_film_, a, cl_double(double(stats_.passes)), image_buf_);
    enqueue_1d(dc_.queue, k_film_, num_pixels_);
    return read_film(dc_, image_buf_, scene_.camera.width, scene_.camera.height);
}

} // namespace clppm
