#include "integrators/photon_mapping_integrator.h"

#include "integrators/checkpoint_checks.h"
#include "integrators/direct_light.h"
#include "integrators/progressive_update.h"
#include "util/error.h"

namespace clppm {

PhotonMappingIntegrator::PhotonMappingIntegrator(const DeviceContext& dc, const DeviceScene& scene,
                                                 const RenderSettings& settings, const cl::Program& program,
                                                 const SecondaryDevices& secondaries)
    : IntegratorBase(dc, scene, settings, program) {
    if (settings.visual_importance && settings.integrator == "pppm")
        throw Error("--visual-importance: PPPM's passes are independent estimates; use --integrator sppm or ppm");
    photons_ = std::make_unique<PhotonPasses>(dc, scene, settings_, program, stats_, secondaries.devices,
                                              secondaries.program_file, secondaries.build_options);
    k_eye_ = cl::Kernel(program, "eye_pass");
    k_direct_ = cl::Kernel(program, "direct_light");
    k_update_ = cl::Kernel(program, "ppm_update");
}

void PhotonMappingIntegrator::direct_light(uint64_t pass, uint32_t n) {
    if (settings_.direct == DirectLighting::Sample)
        enqueue_direct_light(dc_, scene_, k_direct_, settings_.seed, pass, hitpoints_, stats_buf_, n, stats_);
}

void PhotonMappingIntegrator::progressive_update(uint32_t n) {
    if (errors_) errors_->update(passflux_, hitpoints_, stats_buf_, 0.0, power_per_photon());
    auto [mean, mx] = enqueue_ppm_update(dc_, k_update_, passflux_, hitpoints_, stats_buf_, n, settings_.alpha,
                                         radius_partials_, stats_);
    if (n > 0) stats_.mean_radius = typical_radius_ = mean, max_radius_ = mx;
}

double PhotonMappingIntegrator::film_photons() const {
    const PhotonChains* chains = photons_->chains();
    return chains ? chains->effective_emitted(stats_.photons_emitted) : double(stats_.photons_emitted);
}

void PhotonMappingIntegrator::save(Checkpoint& ck) {
    IntegratorBase::save(ck);
    save_state(ck);
    ck.put("stats", read_buffer<dev::HitStats>(dc_.queue, stats_buf_, hit_slots_));
    ck.header["typical_radius"] = typical_radius_;
    ck.header["max_radius"] = max_radius_;
    if (PhotonChains* chains = photons_->chains()) chains->save(ck);
    save_error_stats(ck);
}

void PhotonMappingIntegrator::restore(const Checkpoint& ck) {
    IntegratorBase::restore(ck);
    check_photon_counters(ck, stats_, settings_.photons, scene_.info.radius);
    const double r0 = stats_.initial_radius; // the radii only shrink from it
    std::vector<dev::HitStats> hstats = ck.get<dev::HitStats>("stats", hit_slots_);
    if (stats_.hitpoints > 0) check_hit_stats(ck, hstats, r0 * r0 * (1 + 1e-9));
    write_buffer(dc_.queue, stats_buf_, hstats);
    typical_radius_ = checkpoint_number(ck, "typical_radius", 0, r0 * (1 + 1e-9));
    max_radius_ = checkpoint_number(ck, "max_radius", 0, r0 * (1 + 1e-9));
    if (PhotonChains* chains = photons_->chains()) chains->restore(ck);
    restore_error_stats(ck, stats_buf_);
    restore_state(ck);
}

} // namespace clppm
