#include "integrators/photon_passes.h"

#include <chrono>
#include <exception>
#include <thread>

#include "device/kernel_launch.h"
#include "device/kernel_program.h"
#include "util/error.h"

namespace clppm {

namespace {

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

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
    double seconds = 0;
    std::exception_ptr error;

    Worker(const DeviceInfo& info, const DeviceContext& primary, const DeviceScene& primary_scene,
           const RenderSettings& settings, const std::string& file, const std::string& options)
        : dc(info), scene(primary_scene.clone_to(primary, dc)), program(build_program(dc, file, options)) {
        map = std::make_unique<PhotonMap>(dc, scene, settings, program, stats);
    }

    void ensure(uint32_t n) {
        if (n <= capacity) return;
        capacity = n;
        hitpoints = cl::Buffer(dc.context, CL_MEM_READ_ONLY, size_t(n) * sizeof(dev::HitPoint));
        hstats = cl::Buffer(dc.context, CL_MEM_READ_ONLY, size_t(n) * sizeof(dev::HitStats));
        out = cl::Buffer(dc.context, CL_MEM_READ_WRITE, size_t(n) * sizeof(dev::PassFlux));
    }
};

PhotonPasses::PhotonPasses(const DeviceContext& primary, const DeviceScene& scene, const RenderSettings& settings,
                           const cl::Program& program, IntegratorStats& stats,
                           const std::vector<DeviceInfo>& secondaries, const std::string& program_file,
                           const std::string& build_options)
    : dc_(primary), settings_(settings), stats_(stats), primary_(primary, scene, settings, program, stats) {
    for (const DeviceInfo& info : secondaries)
        workers_.push_back(std::make_unique<Worker>(info, primary, scene, settings, program_file, build_options));
    // Until measured, share by compute units.
    rate_.push_back(std::max(1u, primary.info.compute_units));
    for (const auto& w : workers_) rate_.push_back(std::max(1u, w->dc.info.compute_units));
}

PhotonPasses::~PhotonPasses() = default;

void PhotonPasses::set_second_gather(const cl::Kernel& kernel, const cl::Buffer& out, const std::string& phase) {
    if (!workers_.empty()) throw Error(phase + " runs on one device only: give a single --device");
    primary_.set_second_gather(kernel, out, phase);
}

std::vector<uint32_t> PhotonPasses::split(uint32_t photons) const {
    double total = 0;
    for (double r : rate_) total += r;
    std::vector<uint32_t> s(rate_.size(), 0);
    uint32_t given = 0;
    for (size_t k = 1; k < s.size(); ++k) {
        s[k] = uint32_t(double(photons) * rate_[k] / total);
        given += s[k];
    }
    s[0] = photons - given; // the primary takes the rounding
    return s;
}

void PhotonPasses::run_pass(uint64_t pass, const cl::Buffer& hitpoints, const cl::Buffer& stats, uint32_t n,
                            float global_r2, double typical_radius, double max_radius, const cl::Buffer& out) {
    const uint32_t M = uint32_t(settings_.photons);
    if (workers_.empty()) {
        primary_.run_pass(pass, 0, M, hitpoints, stats, n, global_r2, typical_radius, max_radius, out);
        split_ = {M};
        stats_.device_photons = split_;
        return;
    }
    split_ = split(M);
    stats_.device_photons = split_;
    // The secondaries gather for the primary's hit points with the primary's radii.
    const bool send_hitpoints = !hitpoints_fixed_ || hitpoints_sent_ != n;
    std::vector<dev::HitPoint> hp;
    if (send_hitpoints) hp = read_buffer<dev::HitPoint>(dc_.queue, hitpoints, n);
    hitpoints_sent_ = n;
    std::vector<dev::HitStats> hs = read_buffer<dev::HitStats>(dc_.queue, stats, n);
    std::vector<std::thread> threads;
    uint32_t first = split_[0];
    for (size_t k = 0; k < workers_.size(); ++k) {
        Worker& w = *workers_[k];
        const uint32_t begin = first, count = split_[k + 1];
        first += count;
        threads.emplace_back([&, begin, count] {
            try {
                const double t0 = now_s();
                w.ensure(std::max<uint32_t>(1, n));
                if (send_hitpoints) write_buffer(w.dc.queue, w.hitpoints, hp);
                write_buffer(w.dc.queue, w.hstats, hs);
                w.map->run_pass(pass, begin, count, w.hitpoints, w.hstats, n, global_r2, typical_radius, max_radius,
                                w.out);
                w.result = read_buffer<dev::PassFlux>(w.dc.queue, w.out, n);
                collect_event_times(w.stats);
                w.seconds = now_s() - t0;
            } catch (...) {
                w.error = std::current_exception();
            }
        });
    }
    const double t0 = now_s();
    std::vector<dev::PassFlux> sum;
    std::exception_ptr primary_error;
    try {
        primary_.run_pass(pass, 0, split_[0], hitpoints, stats, n, global_r2, typical_radius, max_radius, out);
        sum = read_buffer<dev::PassFlux>(dc_.queue, out, n);
    } catch (...) {
        primary_error = std::current_exception(); // after the workers have finished (a cancelled pass)
    }
    const double primary_seconds = now_s() - t0;
    for (std::thread& t : threads) t.join();
    if (primary_error) std::rethrow_exception(primary_error);
    for (const auto& w : workers_)
        if (w->error) std::rethrow_exception(w->error);

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

    // Re-balance: each device's share follows its measured photons per second.
    auto blend = [](double old_rate, uint32_t photons, double seconds) {
        if (photons == 0 || !(seconds > 0)) return old_rate;
        return 0.5 * old_rate + 0.5 * double(photons) / seconds;
    };
    rate_[0] = blend(rate_[0], split_[0], primary_seconds);
    for (size_t k = 0; k < workers_.size(); ++k)
        rate_[k + 1] = blend(rate_[k + 1], split_[k + 1], workers_[k]->seconds);
}

} // namespace clppm
