// Stochastic progressive photon mapping (Hachisuka and Jensen 2009) and probabilistic PPM (Knaus
// and Zwicker 2011): a new eye sample per pixel every pass (anti-aliasing, depth of field, every
// specular choice sampled), statistics per pixel, memory proportional to the pixel count.
#pragma once
#include "integrators/photon_mapping_integrator.h"

namespace clppm {

class SppmIntegrator : public PhotonMappingIntegrator {
public:
    SppmIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                   const cl::Program& program, const SecondaryDevices& secondaries = {});
    // The buffers prepare() (and enable_error_estimation()) allocate for `pixels` pixels.
    static IntegratorMemory memory_needed(size_t pixels, bool error_estimation, bool beams = false);

    void prepare() override;
    void run_pass() override;
    Image image() override;
    // From the next pass on; off unless asked for, so a render without it launches nothing more.
    void enable_error_estimation() override;

private:
    // Visible points are drawn anew every pass from (seed, pass): only the statistics are state,
    // and PPPM's radius.
    void save_state(Checkpoint& ck) const override;
    void restore_state(const Checkpoint& ck) override;
    void eye_pass(uint64_t pass);
    void probabilistic_update();
    // Participating media: the pass's volume hit points' estimates join their pixels' sums
    // (kernels/sppm.cl volume_accumulate), and their radius shrinks.
    void volume_update(uint64_t pass);
    double volume_radius() const;
    double beam_radius() const;

    bool probabilistic_;
    // --volume-gather beams: each pixel's first scattering segment is a beam (kernels/beam.cl), in
    // slot num_pixels_ + i of the hit point buffers.
    bool beams_ = false;
    uint32_t slots_ = 0;   // entries of the hit point, statistics and pass flux buffers
    cl_uint eye_args_ = 0; // eye_pass's parameters: one more (`beams`) in a program with media
    cl::Kernel k_emission_, k_accumulate_, k_volume_, k_beam_accumulate_, k_beam_direct_;
    cl::Buffer sample_emission_;
    double r2_ = 0; // PPPM: this pass's radius squared
    // Media: the volume hit points' radius is volume_r0_ times volume_shrink_^(1/3), the product
    // over the passes so far of (i + alpha) / (i + 1) (Knaus and Zwicker 2011, in 3-D); the beams'
    // is kBeamRadiusScale volume_r0_ times volume_shrink_^(1/2) (a 2-D kernel).
    double volume_r0_ = 0, volume_shrink_ = 1;
};

} // namespace clppm
