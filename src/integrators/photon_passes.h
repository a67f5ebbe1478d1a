// The photon side of a pass on one device or several. With several, each device traces a
// contiguous share of the pass's photon indices (photon i draws from stream (seed, pass, i) on
// whichever device traces it) and gathers them for every hit point; the per-hit-point integer
// flux sums are added in device order on the host. Integer addition is exact, so the image is the
// same bit for bit however the photons are split; the shares follow each device's measured
// photons per second, re-balanced every pass.
//
// With several processes (device/cluster.h: mpirun), the pass's photon indices are first split
// between the ranks by their measured speed (integrators/work_balance.h), each rank splits its
// share between its devices as above, and one MPI reduction per pass adds the ranks' integer sums:
// every rank then holds the same sums, equal bit for bit to one process's.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "integrators/device_fan_out.h"
#include "integrators/photon_map.h"
#include "integrators/work_balance.h"

namespace clppm {

class PhotonPasses {
public:
    // `secondaries` are further devices to share the work with; the program for them is built
    // from program_file with build_options.
    PhotonPasses(const DeviceContext& primary, const DeviceScene& scene, const RenderSettings& settings,
                 const cl::Program& program, IntegratorStats& stats, const std::vector<DeviceInfo>& secondaries,
                 const std::string& program_file, const std::string& build_options);
    ~PhotonPasses();

    // PPM's hit points never change after the eye pass: the secondaries then receive them once
    // instead of every pass.
    void set_hitpoints_fixed(bool fixed) { hitpoints_fixed_ = fixed; }

    // As PhotonMap::run_pass for the pass's whole photon range; hitpoints, stats and out are the
    // primary device's buffers.
    void run_pass(uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                  const PassRadii& radii, const cl::Buffer& out);

    // PhotonMap::set_second_gather on the primary device; with further devices it is an error
    // (their photons would miss the second gather).
    void set_second_gather(const cl::Kernel& kernel, const cl::Buffer& out, const std::string& phase);

    // With --visual-importance, the chains the photons come from (one device, one process).
    PhotonChains* chains() const { return primary_.chains(); }

private:
    struct Worker;
    // This process's photons [first_photon, first_photon + M), on its devices.
    void run_local(uint64_t pass, uint32_t first_photon, uint32_t M, const cl::Buffer& hitpoints,
                   const cl::Buffer& stats, uint32_t n, const PassRadii& radii, const cl::Buffer& out);

    const DeviceContext& dc_;
    const RenderSettings& settings_;
    IntegratorStats& stats_;
    PhotonMap primary_;
    std::vector<std::unique_ptr<Worker>> workers_;
    DeviceFanOut fan_out_;
    std::vector<uint32_t> split_;
    bool hitpoints_fixed_ = false;
    uint32_t hitpoints_sent_ = 0; // hit points the secondaries hold (fixed hit points only)
    cl::Buffer second_out_;       // the second gather's output, summed over ranks with the flux
    WorkBalance rank_balance_;    // this rank's seconds against its photons, for the ranks' split
    std::vector<uint32_t> rank_split_;
};

} // namespace clppm
