#include "integrators/pixel_share.h"

#include "device/cluster.h"
#include "device/kernel_launch.h"

namespace clppm {

PixelRanges split_pixels(uint32_t num_pixels, const WorkBalance& mine) {
    PixelRanges r;
    r.count = num_pixels;
    Cluster& cl = cluster();
    if (!cl.distributed()) return r;
    size_t at = 0;
    for (uint32_t c : ranks_split(num_pixels, mine)) {
        r.firsts.push_back(at);
        r.counts.push_back(c);
        at += c;
    }
    r.first = uint32_t(r.firsts[size_t(cl.rank())]);
    r.count = uint32_t(r.counts[size_t(cl.rank())]);
    return r;
}

void share_pixels(const cl::CommandQueue& queue, const cl::Buffer& buffer, size_t doubles_per_pixel,
                  const PixelRanges& ranges, uint32_t num_pixels) {
    std::vector<double> host(size_t(num_pixels) * doubles_per_pixel);
    const size_t me = size_t(cluster().rank());
    const size_t offset = ranges.firsts[me] * doubles_per_pixel, n = ranges.counts[me] * doubles_per_pixel;
    if (n) queue.enqueueReadBuffer(buffer, CL_TRUE, offset * sizeof(double), n * sizeof(double), host.data() + offset);
    std::vector<size_t> f(ranges.firsts), c(ranges.counts);
    for (size_t r = 0; r < f.size(); ++r) f[r] *= doubles_per_pixel, c[r] *= doubles_per_pixel;
    cluster().share_slices(host.data(), f, c);
    write_buffer(queue, buffer, host);
}

} // namespace clppm
