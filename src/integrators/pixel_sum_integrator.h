// What the integrators that add one sample per pixel and pass to a running sum share (the path
// tracer, VCM and BPT): the sum, three doubles a pixel, and its film, the mean over the passes;
// their checkpoint; their error estimate, from the spread of each pixel's samples over the passes
// (kernels/pt_error.cl); and the split of a pass's pixels between processes (integrators/pixel_share.h):
// each rank renders a contiguous range by its measured speed, then every rank receives every other
// range, so that all hold one process's image bit for bit (a pixel's sample depends on (seed,
// pass, pixel) alone).
#pragma once
#include <cstddef>

#include "integrators/integrator.h"
#include "integrators/pixel_share.h"
#include "integrators/work_balance.h"

namespace clppm {

class PixelSumIntegrator : public IntegratorBase {
public:
    Image image() override;
    // From the spread of the passes' samples, from the next pass on, without a bias term: the path
    // tracer and BPT are unbiased, and VCM's merging bias is measured to stay inside the estimate's
    // calibration (bench/ERROR_CALIBRATION.md).
    void enable_error_estimation() override;

protected:
    static constexpr size_t kSumBytesPerPixel = 3 * sizeof(cl_double);
    // What error estimation adds to `m` for `pixels` pixels.
    static IntegratorMemory with_error_estimation(IntegratorMemory m, size_t pixels);

    PixelSumIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                       const cl::Program& program);
    // The running sum, zeroed, and the film; the error statistics start from it.
    void allocate_sum();
    // This process's pixels of the next pass (all of them without MPI); times the pass.
    PixelRanges begin_pass();
    // Once the pass's samples are in the sum: the error statistics take them, every rank receives
    // every range of the sum and of the statistics, the pass is counted (`passes` of them for a
    // batch, which neither error statistics nor several ranks allow: passes_batchable()).
    void end_pass(const PixelRanges& ranges, uint64_t passes = 1);
    // Whether several passes may run in one launch: not while estimating the error (its
    // statistics take each pass's samples apart) nor across processes (they exchange every pass).
    bool passes_batchable() const;
    // The sum (and the error statistics) into a checkpoint and back, checked finite and >= 0.
    void save_sum(Checkpoint& ck) const;
    void restore_sum(const Checkpoint& ck);
    // Whether a pixel's passes are Sobol' points rather than independent: the estimate then
    // measures how much closer their mean is than their spread says.
    virtual bool sobol_passes() const { return false; }

    cl::Kernel k_film_;
    cl::Buffer accum_, image_buf_;

private:
    WorkBalance balance_; // this rank's seconds against its pixels, for the ranks' split
    double pass_start_s_ = 0;
};

} // namespace clppm
