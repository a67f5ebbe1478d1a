#include "integrators/photon_map.h"

#include <algorithm>
#include <cmath>

#include "device/kernel_launch.h"
#include "scene/open_edges.h"

namespace clppm {

namespace {

// Uniform paths each traced item takes: one per photon, or PHOTON_CHAIN_STEPS per chain.
uint64_t paths_per_item(const RenderSettings& settings) { return settings.visual_importance ? PHOTON_CHAIN_STEPS : 1; }

} // namespace

PhotonMap::PhotonMap(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                     const cl::Program& program, IntegratorStats& stats, uint64_t max_batch_photons)
    : dc_(dc), scene_(scene), settings_(settings), stats_(stats), grid_(dc, program, stats), program_(program),
      trace_(dc, sizeof(dev::Photon), kStoredPerEmitted * paths_per_item(settings),
             std::min<uint64_t>({(settings.photons + paths_per_item(settings) - 1) / paths_per_item(settings),
                                 kMaxBatchPhotons / paths_per_item(settings),
                                 max_batch_photons > 0 ? max_batch_photons : ~0ull}),
             settings.visual_importance ? "a single photon chain" : "a single photon", "hits") {
    if (settings.visual_importance) {
        k_photon_ = cl::Kernel(program, "photon_chain_trace");
        chains_ = std::make_unique<PhotonChains>(dc, program, stats,
                                                 (settings.photons + PHOTON_CHAIN_STEPS - 1) / PHOTON_CHAIN_STEPS);
    } else {
        k_photon_ = cl::Kernel(program, "photon_trace");
    }
    k_gather_ = cl::Kernel(program, "gather");
    k_coverage_ = cl::Kernel(program, "disc_coverage");
}

size_t PhotonMap::memory_needed(const RenderSettings& settings, const DeviceInfo& device, uint64_t hitpoints) {
    const uint64_t capacity = BatchedTrace::initial_capacity(std::min<uint64_t>(settings.photons, kMaxBatchPhotons),
                                                             kStoredPerEmitted, sizeof(dev::Photon), device);
    // With beams, a second grid and sorted copy of the photons stored in media (beam_gather: at most
    // all of them).
    const size_t beams = settings.volume_gather == VolumeGather::Beams
                             ? size_t(capacity) * sizeof(dev::Photon) + HashGrid::bytes_for(capacity)
                             : 0;
    return 2 * size_t(capacity) * sizeof(dev::Photon) + HashGrid::bytes_for(capacity) + beams +
           (settings.visual_importance
                ? PhotonChains::memory_needed((settings.photons + PHOTON_CHAIN_STEPS - 1) / PHOTON_CHAIN_STEPS,
                                              hitpoints)
                : 0);
}

size_t PhotonMap::device_bytes() const {
    return trace_.device_bytes() + grid_.device_bytes() + (chains_ ? chains_->device_bytes() : 0) +
           (beam_grid_ ? beam_grid_->device_bytes() + beam_sorted_bytes_ : 0);
}

void PhotonMap::run_pass(uint64_t pass, uint32_t first_photon, uint32_t count_photons, const cl::Buffer& hitpoints,
                         const cl::Buffer& stats, uint32_t n, const PassRadii& radii, const cl::Buffer& out) {
    batches_ = 0;
    if (count_photons == 0) {
        if (n > 0) fill_buffer(dc_.queue, out, cl_uchar(0), 0, size_t(n) * sizeof(dev::PassFlux));
        return;
    }
    measure_coverage(pass, hitpoints, stats, n, radii.global_r2);
    if (chains_) { // where hit points may gather: cells of the initial radius
        const double cell = std::max(radii.max, 2.0 * scene_.info.radius / double(1 << 20));
        chains_->mark(hitpoints, stats, n, radii.global_r2, scene_.bounds_min, cell);
        chains_->begin_pass();
    }
    // Items: photons [first, first + count), or with chains every chain (one device and process).
    const uint32_t first_item = chains_ ? 0 : first_photon;
    const uint32_t end_item = chains_
                                  ? uint32_t((uint64_t(count_photons) + PHOTON_CHAIN_STEPS - 1) / PHOTON_CHAIN_STEPS)
                                  : first_photon + count_photons;
    trace_.run(
        first_item, end_item, [&](uint32_t first, uint32_t count) { trace(pass, first, count); },
        [&](uint32_t, uint32_t, uint32_t stored) {
            if (chains_) chains_->commit_batch();
            build_grid(stored, radii);
            gather(pass, hitpoints, stats, n, radii, batches_ > 0, out);
            if (radii.beam_r2 > 0) beam_gather(stored, pass, hitpoints, n, radii.beam_r2, batches_ > 0, out);
            stats_.photons_stored += stored;
            ++batches_;
        });
    if (chains_) chains_->end_pass();
    stats_.photon_bytes = device_bytes();
    stats_.photon_batches = batches_;
}

void PhotonMap::trace(uint64_t pass, uint32_t first, uint32_t count) {
    const int a = set_args(k_photon_, scene_.set_scene_args(k_photon_), cl_ulong(settings_.seed), cl_ulong(pass),
                           cl_uint(first), cl_uint(count), cl_uint(settings_.direct == DirectLighting::Sample ? 1 : 0),
                           trace_.records(), cl_uint(trace_.capacity()), trace_.counter());
    if (chains_) chains_->set_trace_args(k_photon_, a, uint32_t(settings_.photons));
    cl::Event ev;
    enqueue_1d(dc_.queue, k_photon_, count, &ev);
    add_event_time(stats_, "photon_trace", ev);
}

void PhotonMap::build_grid(uint32_t stored, const PassRadii& radii) {
    const double extent = 2.0 * scene_.info.radius;
    const double cell = std::max({2.0 * radii.typical, radii.max / 4.0, extent / double(1 << 20)});
    grid_.build(trace_.records(), trace_.sorted(), stored, scene_.bounds_min, cell);
}

void PhotonMap::gather(uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                       const PassRadii& radii, bool accumulate, const cl::Buffer& out) {
    if (n == 0) return;
    enqueue_gather(k_gather_, pass, hitpoints, stats, n, radii, accumulate, out, "gather");
    if (k_second_())
        enqueue_gather(k_second_, pass, hitpoints, stats, n, radii, accumulate, second_out_, second_phase_);
}

// The beams' gather (kernels/beam.cl) over its own grid of the photons stored in media, after
// gather wrote the other slots: cells of side 2 r (side r ran half the passes in the volumetric
// caustic: more cells for each step along a beam; bench/RESULTS.md).
void PhotonMap::beam_gather(uint32_t stored, uint64_t pass, const cl::Buffer& hitpoints, uint32_t n, float beam_r2,
                            bool accumulate, const cl::Buffer& out) {
    if (n == 0) return;
    if (!beam_grid_) {
        k_beam_ = cl::Kernel(program_, "beam_gather");
        beam_grid_ = std::make_unique<HashGrid>(dc_, program_, stats_, "beam_");
    }
    const size_t bytes = std::max<size_t>(1, stored) * sizeof(dev::Photon);
    if (bytes > beam_sorted_bytes_) {
        beam_sorted_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, bytes);
        beam_sorted_bytes_ = bytes;
    }
    const double cell = std::max(2.0 * std::sqrt(double(beam_r2)), 2.0 * scene_.info.radius / double(1 << 20));
    beam_grid_->build(trace_.records(), beam_sorted_, stored, scene_.bounds_min, cell);
    set_args(k_beam_, 0, beam_grid_->info(), beam_sorted_, beam_grid_->starts(), hitpoints, cl_uint(n),
             cl_float(beam_r2), cl_uint(accumulate ? 1 : 0), out, cl_ulong(settings_.seed), cl_ulong(pass));
    cl::Event ev;
    enqueue_1d(dc_.queue, k_beam_, n, &ev);
    add_event_time(stats_, "beam_gather", ev);
}

// gather and the second gather take the same arguments, each with its own output; the seed and
// the pass give the pass's wavelength (kernels/dispersion.cl).
void PhotonMap::enqueue_gather(cl::Kernel& kernel, uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats,
                               uint32_t n, const PassRadii& radii, bool accumulate, const cl::Buffer& out,
                               const std::string& phase) {
    set_args(kernel, 0, grid_.info(), trace_.sorted(), grid_.starts(), hitpoints, stats, cl_uint(n),
             cl_float(radii.global_r2), cl_float(radii.volume_r2), cl_uint(accumulate ? 1 : 0), out,
             cl_ulong(settings_.seed), cl_ulong(pass), coverage_);
    cl::Event ev;
    enqueue_1d(dc_.queue, kernel, n, &ev);
    add_event_time(stats_, phase, ev);
}

// Each hit point's covered fraction of its gather disc at this pass's radius, which the gathers
// divide by (kernels/disc_coverage.cl), or every disc whole (1) where --disc-coverage says so.
void PhotonMap::measure_coverage(uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                                 float global_r2) {
    if (n == 0) return;
    if (n > coverage_capacity_) {
        coverage_ = make_buffer(dc_.context, CL_MEM_READ_WRITE, size_t(n) * sizeof(cl_float2));
        coverage_capacity_ = n;
    }
    if (!disc_coverage_wanted(settings_.disc_coverage, n, settings_.photons)) {
        fill_buffer(dc_.queue, coverage_, cl_float2{{1.0f, 1.0f}}, 0, size_t(n) * sizeof(cl_float2));
        return;
    }
    if (!open_edges_()) { // the scene's open edges, from the blocks as the device has them
        const size_t bytes = scene_.tri_blocks_buf.getInfo<CL_MEM_SIZE>();
        std::vector<dev::BvhTriBlock> blocks(bytes / sizeof(dev::BvhTriBlock));
        dc_.queue.enqueueReadBuffer(scene_.tri_blocks_buf, CL_TRUE, 0, blocks.size() * sizeof(dev::BvhTriBlock),
                                    blocks.data());
        std::vector<uint8_t> open = open_edges(blocks, scene_.info.num_tris);
        if (open.empty()) open.push_back(0); // a buffer cannot be empty
        open_edges_ = make_buffer(dc_.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, open.size(), open.data());
    }
    set_args(k_coverage_, scene_.set_scene_args(k_coverage_), open_edges_, hitpoints, stats, cl_uint(n),
             cl_float(global_r2), cl_ulong(settings_.seed), cl_ulong(pass), coverage_);
    cl::Event ev;
    enqueue_1d(dc_.queue, k_coverage_, n, &ev);
    add_event_time(stats_, "disc coverage", ev);
}

void PhotonMap::set_second_gather(const cl::Kernel& kernel, const cl::Buffer& out, const std::string& phase) {
    k_second_ = kernel;
    second_out_ = out;
    second_phase_ = phase;
}

} // namespace clppm
