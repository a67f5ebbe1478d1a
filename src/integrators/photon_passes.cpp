#include "integrators/photon_passes.h"

#include "device/cluster.h"
#include "device/kernel_launch.h"
#include "device/kernel_program.h"
#include "integrators/work_balance.h"
#include "util/error.h"
#include "util/steady_seconds.h"

namespace clppm {

namespace {

std::vector<unsigned> compute_units(const DeviceInfo& primary, const std::vector<DeviceInfo>& secondaries) {
    std::vector<unsigned> cu{primary.compute_units};
    for (const DeviceInfo& d : secondaries) cu.push_back(d.compute_units);
    return cu;
}

} // namespace

// A further device: its own context, copy of the scene, program, photon map and buffers.
struct PhotonPasses::Worker {
    DeviceContext dc;
    DeviceScene scene;
    cl::Program program;
    IntegratorStats stats;
    std::unique_ptr<PhotonMap> map;
    cl::Buffer hitpoints, hstats, out;
    uint32_t capacity = 0;
    std::vector<dev::PassFlux> result;

    Worker(const DeviceInfo& info, const DeviceContext& primary, const DeviceScene& primary_scene,
           const RenderSettings& settings, const std::string& file, const std::string& options)
        : dc(info), scene(primary_scene.clone_to(primary, dc)), program(build_program(dc, file, options)) {
        map = std::make_unique<PhotonMap>(dc, scene, settings, program, stats);
    }

    void ensure(uint32_t n) {
        if (n <= capacity) return;
        capacity = n;
        hitpoints = make_buffer(dc.context, CL_MEM_READ_ONLY, size_t(n) * sizeof(dev::HitPoint));
        hstats = make_buffer(dc.context, CL_MEM_READ_ONLY, size_t(n) * sizeof(dev::HitStats));
        out = make_buffer(dc.context, CL_MEM_READ_WRITE, size_t(n) * sizeof(dev::PassFlux));
    }
};

PhotonPasses::PhotonPasses(const DeviceContext& primary, const DeviceScene& scene, const RenderSettings& settings,
                           const cl::Program& program, IntegratorStats& stats,
                           const std::vector<DeviceInfo>& secondaries, const std::string& program_file,
                           const std::string& build_options)
    : dc_(primary), settings_(settings), stats_(stats), primary_(primary, scene, settings, program, stats),
      fan_out_(compute_units(primary.info, secondaries)) {
    // A chain lives on the device and in the process that traces its photon index every pass.
    if (settings.visual_importance && (!secondaries.empty() || cluster().distributed()))
        throw Error("--visual-importance runs on one device in one process: give a single --device, no mpirun");
    for (const DeviceInfo& info : secondaries)
        workers_.push_back(std::make_unique<Worker>(info, primary, scene, settings, program_file, build_options));
}

PhotonPasses::~PhotonPasses() = default;

void PhotonPasses::set_second_gather(const cl::Kernel& kernel, const cl::Buffer& out, const std::string& phase) {
    if (!workers_.empty()) throw Error(phase + " runs on one device only: give a single --device");
    primary_.set_second_gather(kernel, out, phase);
    second_out_ = out; // summed over ranks with the flux (cluster.h)
}

void PhotonPasses::run_pass(uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                            const PassRadii& radii, const cl::Buffer& out) {
    Cluster& cl = cluster();
    const uint32_t M = uint32_t(settings_.photons);
    // This rank's share of the pass's photon indices, [first, first + count): in proportion to the
    // ranks' measured photons per second, which every rank knows alike (all_values), so every rank
    // computes the same split.
    uint32_t first = 0, count = M;
    if (cl.distributed()) {
        rank_split_ = ranks_split(M, rank_balance_);
        for (int r = 0; r < cl.rank(); ++r) first += rank_split_[size_t(r)];
        count = rank_split_[size_t(cl.rank())];
    }
    const double t0 = steady_seconds();
    const uint64_t stored_before = stats_.photons_stored;
    run_local(pass, first, count, hitpoints, stats, n, radii, out);
    stats_.local_work += count;
    if (!cl.distributed()) return;
    // One reduction per pass: the flux sums (PassFlux: three int64 and the count m in the low half
    // of a fourth, whose high half is padding and stays 0), the second gather's int64 per hit point
    // (error estimation) and the photons stored. Integer sums: exact, in any order.
    static_assert(sizeof(dev::PassFlux) == 4 * sizeof(int64_t), "PassFlux is summed as four int64");
    const bool second = second_out_() != nullptr;
    std::vector<int64_t> v(size_t(n) * (4 + (second ? 1 : 0)) + 1, 0);
    if (n > 0) {
        dc_.queue.enqueueReadBuffer(out, CL_TRUE, 0, size_t(n) * sizeof(dev::PassFlux), v.data());
        if (second)
            dc_.queue.enqueueReadBuffer(second_out_, CL_TRUE, 0, size_t(n) * sizeof(int64_t), v.data() + size_t(n) * 4);
    }
    v.back() = int64_t(stats_.photons_stored - stored_before);
    rank_balance_.record(count, steady_seconds() - t0); // this rank's own work, up to its sums read back
    cl.sum(v.data(), v.size());
    if (n > 0) {
        write_bytes(dc_.queue, out, 0, size_t(n) * sizeof(dev::PassFlux), v.data());
        if (second) write_bytes(dc_.queue, second_out_, 0, size_t(n) * sizeof(int64_t), v.data() + size_t(n) * 4);
    }
    stats_.photons_stored = stored_before + uint64_t(v.back());
    stats_.rank_photons = rank_split_;
}

void PhotonPasses::run_local(uint64_t pass, uint32_t first_photon, uint32_t M, const cl::Buffer& hitpoints,
                             const cl::Buffer& stats, uint32_t n, const PassRadii& radii, const cl::Buffer& out) {
    if (workers_.empty()) {
        primary_.run_pass(pass, first_photon, M, hitpoints, stats, n, radii, out);
        split_ = {M};
        stats_.device_photons = split_;
        return;
    }
    split_ = fan_out_.split(M);
    stats_.device_photons = split_;
    // The secondaries gather for the primary's hit points with the primary's radii.
    const bool send_hitpoints = !hitpoints_fixed_ || hitpoints_sent_ != n;
    std::vector<dev::HitPoint> hp;
    if (send_hitpoints) hp = read_buffer<dev::HitPoint>(dc_.queue, hitpoints, n);
    hitpoints_sent_ = n;
    std::vector<dev::HitStats> hs = read_buffer<dev::HitStats>(dc_.queue, stats, n);
    std::vector<dev::PassFlux> sum;
    fan_out_.run(first_photon, split_, [&](size_t k, uint32_t begin, uint32_t count) {
        if (k == 0) {
            primary_.run_pass(pass, begin, count, hitpoints, stats, n, radii, out);
            sum = read_buffer<dev::PassFlux>(dc_.queue, out, n);
            return;
        }
        Worker& w = *workers_[k - 1];
        w.ensure(std::max<uint32_t>(1, n));
        if (send_hitpoints) write_buffer(w.dc.queue, w.hitpoints, hp);
        write_buffer(w.dc.queue, w.hstats, hs);
        w.map->run_pass(pass, begin, count, w.hitpoints, w.hstats, n, radii, w.out);
        w.result = read_buffer<dev::PassFlux>(w.dc.queue, w.out, n);
        collect_event_times(w.stats);
    });

    // Fixed order, integer sums: the same totals for any split.
    uint64_t stored = 0;
    for (const auto& w : workers_) {
        for (uint32_t i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) sum[i].flux[c] += w->result[i].flux[c];
            sum[i].m += w->result[i].m;
        }
        stored += w->stats.photons_stored;
        w->stats.photons_stored = 0;
    }
    write_buffer(dc_.queue, out, sum);
    stats_.photons_stored += stored;
}

} // namespace clppm
