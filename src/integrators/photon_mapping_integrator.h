// What PPM and SPPM/PPPM share (Hachisuka et al. 2008, Sec. 4; Hachisuka and Jensen 2009): hit
// points with their statistics (R, N, tau per point), each pass's photons gathered into them
// (integrators/photon_passes.h, on several devices and processes), direct light sampled at them,
// the progressive update (Eqs. 7-10), and their part of a checkpoint. PPM keeps its hit points;
// SPPM draws them anew every pass.
#pragma once
#include <cstdint>
#include <memory>

#include "integrators/integrator.h"
#include "integrators/photon_passes.h"

namespace clppm {

class PhotonMappingIntegrator : public IntegratorBase {
public:
    // The hit statistics (R, N, tau, direct light), the grid's radii and the error statistics,
    // with what save_state() adds; restored with every field checked.
    void save(Checkpoint& ck) final;
    void restore(const Checkpoint& ck) final;

protected:
    PhotonMappingIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                            const cl::Program& program, const SecondaryDevices& secondaries);

    // Explicit direct light (--direct sample) at the n hit points, pass `pass`.
    void direct_light(uint64_t pass, uint32_t n);
    // Eqs. 7-10 with this pass's M(x) and Phi_M(x) over the n hit points; before it, the error
    // statistics take this pass's gather while the statistics still hold the radii it used.
    void progressive_update(uint32_t n);
    // What else a checkpoint holds of the integrator (restored after the hit statistics).
    virtual void save_state(Checkpoint& ck) const = 0;
    virtual void restore_state(const Checkpoint& ck) = 0;
    // The photon count the film divides tau by: N_emitted, or with --visual-importance the
    // chains' effective count (PhotonChains::effective_emitted).
    double film_photons() const;
    // Phi / M: the power each photon of a pass carries.
    double power_per_photon() const { return double(scene_.info.total_power) / double(settings_.photons); }
    // What a photon of the pass now ending carries in the error statistics: Phi / M, or with
    // --visual-importance Phi over the pass's share of the chains' effective count after it, so
    // that the mean of the passes' estimates is the film's image.
    double error_power_per_photon() const;
    // With --visual-importance the film divides by the chains' effective count, N_states N_U / V_c:
    // the visible fraction V_c / N_U is estimated, one factor for every pixel and pass, with
    // relative variance (1 - p) / V_c ~ 1 / V_c (binomial). 0 without chains.
    double normalization_variance() const override;

    std::unique_ptr<PhotonPasses> photons_;
    cl::Kernel k_eye_, k_direct_, k_update_, k_film_;
    cl::Buffer hitpoints_, stats_buf_, passflux_, image_buf_, radius_partials_;
    uint32_t hit_slots_ = 0;    // entries the hit point buffers hold
    double typical_radius_ = 0; // mean R over hit points: sizes the next grid's cells
    double max_radius_ = 0;
    uint64_t states_before_pass_ = 0; // the chains' deposited states before this pass (error_power_per_photon)
    // Volume hit points keep statistics of their own, shrinking in 3-D (PPM's fixed ones); SPPM's
    // and PPPM's take one radius a pass instead (SppmIntegrator::volume_update).
    bool volume_stats_ = false;
};

} // namespace clppm
