// A pass's work shared between this process's devices: device k takes a contiguous share of the
// units (photons, or pixels) in proportion to its measured units per second (smoothed over the
// passes; by compute units until measured), the first device taking the rounding. All devices run
// at once, the first on the calling thread and each other on a thread of its own; an error on any
// (a cancelled pass) is rethrown once every device has finished, the first device's first. The
// photon integrators (integrators/photon_passes.h) and VCM (integrators/vcm_integrator.h) share it.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

namespace clppm {

class DeviceFanOut {
public:
    // One entry per device, the primary first: its compute units, the speed assumed until measured.
    explicit DeviceFanOut(const std::vector<unsigned>& compute_units);

    size_t devices() const { return rate_.size(); }
    // `total` units shared in proportion to the rates; the first device takes the rounding.
    std::vector<uint32_t> split(uint32_t total) const;
    // work(k, first, count) for every device k at once, over consecutive ranges of `shares` from
    // `first`; then each device's rate follows its measured time.
    void run(uint32_t first, const std::vector<uint32_t>& shares,
             const std::function<void(size_t device, uint32_t first, uint32_t count)>& work);

private:
    std::vector<double> rate_; // units per second per device, smoothed
};

} // namespace clppm
