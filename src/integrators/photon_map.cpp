#include "integrators/photon_map.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "device/kernel_launch.h"
#include "util/cancellation.h"
#include "util/error.h"

namespace clppm {

namespace {

// The photon buffers' budget: one within the device's largest allocation, and both of them
// (traced and sorted) within a quarter of its memory.
uint64_t photon_capacity_budget(const DeviceInfo& device) {
    return std::min<uint64_t>(
        {device.max_alloc / sizeof(dev::Photon), device.global_mem / 4 / (2 * sizeof(dev::Photon)), 0x7fffffffu});
}

} // namespace

PhotonMap::PhotonMap(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                     const cl::Program& program, IntegratorStats& stats, uint64_t max_batch_photons)
    : dc_(dc), scene_(scene), settings_(settings), stats_(stats), grid_(dc, program, stats) {
    k_photon_ = cl::Kernel(program, "photon_trace");
    k_gather_ = cl::Kernel(program, "gather");
    counter_ = cl::Buffer(dc.context, CL_MEM_READ_WRITE, sizeof(cl_uint));
    max_capacity_ = photon_capacity_budget(dc.info);
    uint64_t batch = std::min<uint64_t>(settings.photons, kMaxBatchPhotons);
    if (max_batch_photons > 0) batch = std::min(batch, max_batch_photons);
    if (const char* e = std::getenv("CLPPM_PHOTON_BATCH"); e && *e)
        batch = std::min<uint64_t>(batch, std::strtoull(e, nullptr, 10));
    batch = std::min<uint64_t>(batch, std::max<uint64_t>(1, max_capacity_ / kStoredPerEmitted));
    batch_ = uint32_t(std::max<uint64_t>(1, batch));
}

size_t PhotonMap::memory_needed(const RenderSettings& settings, const DeviceInfo& device) {
    // As run_pass allocates: kStoredPerEmitted per photon, at least 1024, within the budget.
    const uint64_t batch = std::min<uint64_t>(settings.photons, kMaxBatchPhotons);
    const uint64_t capacity =
        std::clamp<uint64_t>(batch * kStoredPerEmitted, 1024, std::max<uint64_t>(1024, photon_capacity_budget(device)));
    return 2 * size_t(capacity) * sizeof(dev::Photon) + HashGrid::bytes_for(capacity);
}

size_t PhotonMap::device_bytes() const { return 2 * size_t(capacity_) * sizeof(dev::Photon) + grid_.device_bytes(); }

void PhotonMap::allocate(uint32_t capacity) {
    capacity_ = capacity;
    photons_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, size_t(capacity_) * sizeof(dev::Photon));
    sorted_ = cl::Buffer(dc_.context, CL_MEM_READ_WRITE, size_t(capacity_) * sizeof(dev::Photon));
}

void PhotonMap::run_pass(uint64_t pass, uint32_t first_photon, uint32_t count_photons, const cl::Buffer& hitpoints,
                         const cl::Buffer& stats, uint32_t n, float global_r2, double typical_radius, double max_radius,
                         const cl::Buffer& out) {
    if (count_photons == 0) {
        if (n > 0) dc_.queue.enqueueFillBuffer(out, cl_uchar(0), 0, size_t(n) * sizeof(dev::PassFlux));
        batches_ = 0;
        return;
    }
    const uint32_t end = first_photon + count_photons;
    if (capacity_ == 0)
        allocate(uint32_t(
            std::clamp<uint64_t>(uint64_t(batch_) * kStoredPerEmitted, 1024, std::max<uint64_t>(1024, max_capacity_))));
    batches_ = 0;
    for (uint32_t first = first_photon; first < end;) {
        throw_if_cancelled(); // Ctrl-C: abandon the pass; the statistics still hold the last one
        const uint32_t count = std::min(batch_, end - first);
        if (!trace(pass, first, count)) {
            // More stored photons than the buffer holds: grow it within the budget, else trace
            // fewer photons at a time. Either way the same photons are traced again.
            uint64_t want = uint64_t(stored_) * 5 / 4 + 1024;
            if (want <= max_capacity_) allocate(uint32_t(want));
            else if (batch_ > 1) batch_ = std::max<uint32_t>(1, batch_ / 2);
            else throw Error("photon pass: a single photon stores more hits than the device memory budget allows");
            continue;
        }
        build_grid(typical_radius, max_radius);
        gather(hitpoints, stats, n, global_r2, batches_ > 0, out);
        stats_.photons_stored += stored_;
        ++batches_;
        first += count;
    }
    stats_.photon_bytes = device_bytes();
    stats_.photon_batches = batches_;
}

bool PhotonMap::trace(uint64_t pass, uint32_t first, uint32_t count) {
    dc_.queue.enqueueFillBuffer(counter_, cl_uint(0), 0, sizeof(cl_uint));
    set_args(k_photon_, scene_.set_scene_args(k_photon_), cl_ulong(settings_.seed), cl_ulong(pass), cl_uint(first),
             cl_uint(count), cl_uint(settings_.direct == DirectLighting::Sample ? 1 : 0), photons_, cl_uint(capacity_),
             counter_);
    cl::Event ev;
    enqueue_1d(dc_.queue, k_photon_, count, &ev);
    cl_uint stored = 0;
    dc_.queue.enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_uint), &stored);
    add_event_time(stats_, "photon_trace", ev);
    stored_ = stored;
    return stored <= capacity_;
}

PhotonMap::~PhotonMap() {
    try {
        dc_.queue.finish();
    } catch (const cl::Error&) { // a lost device: nothing left to wait for
    }
}

void PhotonMap::build_grid(double typical_radius, double max_radius) {
    const double extent = 2.0 * scene_.info.radius;
    const double cell = std::max({2.0 * typical_radius, max_radius / 4.0, extent / double(1 << 20)});
    grid_.build(photons_, sorted_, stored_, scene_.bounds_min, cell);
}

void PhotonMap::gather(const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n, float global_r2,
                       bool accumulate, const cl::Buffer& out) {
    if (n == 0) return;
    enqueue_gather(k_gather_, hitpoints, stats, n, global_r2, accumulate, out, "gather");
    if (k_second_()) enqueue_gather(k_second_, hitpoints, stats, n, global_r2, accumulate, second_out_, second_phase_);
}

// gather and the second gather take the same arguments, each with its own output.
void PhotonMap::enqueue_gather(cl::Kernel& kernel, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                               float global_r2, bool accumulate, const cl::Buffer& out, const std::string& phase) {
    set_args(kernel, 0, grid_.info(), sorted_, grid_.starts(), hitpoints, stats, cl_uint(n), cl_float(global_r2),
             cl_uint(accumulate ? 1 : 0), out);
    cl::Event ev;
    enqueue_1d(dc_.queue, kernel, n, &ev);
    add_event_time(stats_, phase, ev);
}

void PhotonMap::set_second_gather(const cl::Kernel& kernel, const cl::Buffer& out, const std::string& phase) {
    k_second_ = kernel;
    second_out_ = out;
    second_phase_ = phase;
}

} // namespace clppm
