// The interface every integrator offers the render loop: a pass is the unit of work
// (SmallVCM's RunIteration), and the image can be taken at any pass boundary.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "checkpoint.h"
#include "cl.h"
#include "device.h"
#include "image_io.h"
#include "render_scene.h"
#include "render_settings.h"

namespace clppm {

struct IntegratorStats {
    uint64_t passes = 0;
    uint64_t photons_emitted = 0;      // total N_emitted
    uint64_t photons_stored = 0;       // total photon hits stored over all passes
    uint64_t hitpoints = 0;
    double initial_radius = 0;
    double mean_radius = 0;            // current mean R over hit points (PPM)
    std::map<std::string, double> phase_seconds; // device time per phase, from profiling events
    size_t device_bytes = 0;           // integrator buffers (scene buffers are counted apart)
    size_t photon_bytes = 0;           // photon and grid buffers
    uint32_t photon_batches = 0;       // batches the last pass's photons were traced in
    std::vector<uint32_t> device_photons; // photons each device traced in the last pass, primary first
    // Kernel events of the current pass, resolved into phase_seconds at the pass's end so that
    // timing never adds a synchronisation point inside the pass.
    std::vector<std::pair<std::string, cl::Event>> pending_events;
};

class IntegratorBase {
public:
    virtual ~IntegratorBase() = default;
    virtual std::string name() const = 0;
    // Everything before the first refinement pass (PPM: the eye pass).
    virtual void prepare() = 0;
    virtual void run_pass() = 0;
    virtual Image image() = 0;
    const IntegratorStats& stats() const { return stats_; }

    // The progressive state after the last pass, and its restoration after prepare(): the
    // render then continues exactly as if it had never stopped.
    virtual void save(Checkpoint& ck);
    virtual void restore(const Checkpoint& ck);

protected:
    IntegratorStats stats_;
};

// Further devices a photon-mapping integrator shares its photons with, and how to build their
// program (the primary's program file and options).
struct SecondaryDevices {
    std::vector<DeviceInfo> devices;
    std::string program_file, build_options;
};

std::unique_ptr<IntegratorBase> make_integrator(const DeviceContext& dc, const DeviceScene& scene,
                                                const RenderSettings& settings, const cl::Program& program,
                                                const SecondaryDevices& secondaries = {});

// The kernel program an integrator needs, with its build options.
std::string integrator_program_file(const RenderSettings& settings);
// The build options of an integrator's program; `features` (feature_build_options) specialises it
// for a scene, "" builds the generic program.
std::string integrator_build_options(const RenderSettings& settings, const DeviceInfo& device,
                                     const std::string& features = "");

// Reads a whole device buffer of n elements into a vector, and writes one back.
template <class T>
std::vector<T> read_buffer(const cl::CommandQueue& q, const cl::Buffer& b, size_t n) {
    std::vector<T> v(n);
    if (n) q.enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(T), v.data());
    return v;
}
template <class T>
void write_buffer(const cl::CommandQueue& q, const cl::Buffer& b, const std::vector<T>& v) {
    if (!v.empty()) q.enqueueWriteBuffer(b, CL_TRUE, 0, v.size() * sizeof(T), v.data());
}

// Launches a 1-D kernel over n work items (the kernel ignores ids >= n). The work-group size is
// the driver's choice unless CLPPM_LOCAL_SIZE is set, which the tests use to show that images do
// not depend on it.
void enqueue_1d(const cl::CommandQueue& queue, const cl::Kernel& kernel, size_t n, cl::Event* event = nullptr);

// Records a kernel event of phase `phase`; collect_event_times() adds its device time to
// phase_seconds once the pass has finished.
void add_event_time(IntegratorStats& stats, const std::string& phase, const cl::Event& ev);
void collect_event_times(IntegratorStats& stats);

} // namespace clppm
