// Integrators that add one sample per pixel and pass (the path tracer, VCM and BPT) split a pass
// between processes (device/cluster.h) by pixels: each rank traces a contiguous range in
// proportion to its measured speed (integrators/work_balance.h), then every rank receives every
// other's range, so that all hold the whole image as one process would, bit for bit (each pixel's
// sample depends on (seed, pass, pixel) alone).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "device/cl.h"
#include "integrators/work_balance.h"

namespace clppm {

struct PixelRanges {
    std::vector<size_t> firsts, counts; // every rank's range
    uint32_t first = 0, count = 0;      // this rank's
};

// The ranks' ranges of num_pixels pixels by their models; one range of all pixels without MPI.
PixelRanges split_pixels(uint32_t num_pixels, const WorkBalance& mine);

// Every rank's range of `buffer` (doubles_per_pixel doubles a pixel, num_pixels pixels) to every rank.
void share_pixels(const cl::CommandQueue& queue, const cl::Buffer& buffer, size_t doubles_per_pixel,
                  const PixelRanges& ranges, uint32_t num_pixels);

} // namespace clppm
