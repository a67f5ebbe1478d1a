#include "integrators/photon_mapping_integrator.h"

#include <cmath>
#include <limits>

#include "integrators/checkpoint_checks.h"
#include "integrators/direct_light.h"
#include "integrators/integrator_table.h"
#include "integrators/progressive_update.h"
#include "util/error.h"

namespace clppm {

PhotonMappingIntegrator::PhotonMappingIntegrator(const DeviceContext& dc, const DeviceScene& scene,
                                                 const RenderSettings& settings, const cl::Program& program,
                                                 const SecondaryDevices& secondaries)
    : IntegratorBase(dc, scene, settings, program) {
    if (settings.visual_importance && !integrator_row(settings.integrator).visual_importance)
        throw Error("--visual-importance: needs --integrator " + visual_importance_integrators() +
                    " (photon paths that the chains guide)");
    if (settings.visual_importance && scene.media)
        throw Error("--visual-importance: the scene has a participating medium, whose photons the chains do not "
                    "guide yet; leave it off");
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
    if (errors_) errors_->update(passflux_, hitpoints_, stats_buf_, 0.0, error_power_per_photon());
    states_before_pass_ = stats_.chain_counts[CHAIN_STATES];
    auto [mean, mx] = enqueue_ppm_update(dc_, k_update_, passflux_, hitpoints_, stats_buf_, n, settings_.alpha,
                                         volume_stats_, radius_partials_, stats_);
    if (n > 0) stats_.mean_radius = typical_radius_ = mean, max_radius_ = mx;
}

// Called before the pass's counters grow (stats_.passes, photons_emitted), after its chains ended.
// The film divides the sum of all passes' flux by N_states N_U / V_c; this pass's share of that
// count is its own states' (the chains deposit fewer while they look for their first), with the
// visible fraction as now estimated.
double PhotonMappingIntegrator::error_power_per_photon() const {
    if (!photons_->chains()) return power_per_photon();
    const uint64_t states = stats_.chain_counts[CHAIN_STATES] - states_before_pass_;
    const uint64_t visible = stats_.chain_counts[CHAIN_UNIFORM_VISIBLE];
    if (states == 0 || visible == 0) return 0.0;
    const double uniform = double(stats_.photons_emitted + settings_.photons);
    return double(scene_.info.total_power) / (double(states) * uniform / double(visible));
}

double PhotonMappingIntegrator::normalization_variance() const {
    const PhotonChains* chains = photons_->chains();
    if (!chains) return 0;
    const uint64_t visible = stats_.chain_counts[CHAIN_UNIFORM_VISIBLE];
    return visible > 0 ? 1.0 / double(visible) : std::numeric_limits<double>::infinity();
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
    const double r0 = largest_initial_radius(stats_); // the radii only shrink from it
    std::vector<dev::HitStats> hstats = ck.get<dev::HitStats>("stats", hit_slots_);
    if (stats_.hitpoints > 0) check_hit_stats(ck, hstats, r0 * r0 * (1 + 1e-9));
    write_buffer(dc_.queue, stats_buf_, hstats);
    typical_radius_ = checkpoint_number(ck, "typical_radius", 0, r0 * (1 + 1e-9));
    max_radius_ = checkpoint_number(ck, "max_radius", 0, r0 * (1 + 1e-9));
    if (PhotonChains* chains = photons_->chains()) chains->restore(ck);
    states_before_pass_ = stats_.chain_counts[CHAIN_STATES];
    restore_error_stats(ck, stats_buf_);
    restore_state(ck);
}

} // namespace clppm
