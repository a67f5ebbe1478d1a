// What the integrators that add one sample per pixel and pass to a running sum share (the path
// tracer, VCM and BPT): the sum, three doubles a pixel, and its film, the mean over the passes;
// their checkpoint; and the split of a pass's pixels between processes (integrators/pixel_share.h):
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

protected:
    static constexpr size_t kSumBytesPerPixel = 3 * sizeof(cl_double);

    PixelSumIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                       const cl::Program& program);
    // The running sum, zeroed, and the film.
    void allocate_sum();
    // This process's pixels of the next pass (all of them without MPI); times the pass.
    PixelRanges begin_pass();
    // Once the pass's samples are in the sum: every rank receives every range of it (and of
    // `also`, `also_doubles` doubles a pixel: the error statistics), the pass is counted.
    void end_pass(const PixelRanges& ranges, const cl::Buffer* also = nullptr, size_t also_doubles = 0);
    // The sum into a checkpoint and back, checked finite and >= 0.
    void save_sum(Checkpoint& ck) const;
    void restore_sum(const Checkpoint& ck);

    cl::Kernel k_film_;
    cl::Buffer accum_, image_buf_;

private:
    WorkBalance balance_; // this rank's seconds against its pixels, for the ranks' split
    double pass_start_s_ = 0;
};

} // namespace clppm
