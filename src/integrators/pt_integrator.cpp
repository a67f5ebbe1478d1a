#include "integrators/pt_integrator.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>

#include "device/kernel_launch.h"
#include "integrators/checkpoint_checks.h"
#include "integrators/film.h"
#include "util/error.h"

namespace clppm {

PtIntegrator::PtIntegrator(const DeviceContext& dc, const DeviceScene& scene, const RenderSettings& settings,
                           const cl::Program& program, const SecondaryDevices& secondaries)
    : PixelSumIntegrator(dc, scene, settings, program) {
    if (!secondaries.devices.empty()) throw Error("the path tracer renders on one device only");
    k_trace_ = cl::Kernel(program, "path_trace");
    if (settings.sampler == Sampler::ZSobol) screen_log2_ = screen_layout_log2(settings, scene.camera);
}

// L of the screen-space layout: the planned passes rounded up to 2^L (kernels/sobol.cl
// sobol_make_screen, which takes pixel coordinates below 2^16 and L <= 32).
uint32_t PtIntegrator::screen_layout_log2(const RenderSettings& settings, const dev::Camera& camera) {
    if (settings.planned_passes == 0)
        throw Error("--sampler zsobol: its points are laid out for a planned number of passes; give --passes N "
                    "(--time and --target-error may still stop it sooner)");
    if (camera.width > 65536 || camera.height > 65536)
        throw Error("--sampler zsobol: images up to 65536 pixels wide and high; this one is " +
                    std::to_string(camera.width) + "x" + std::to_string(camera.height) + " (--sampler sobol)");
    uint32_t l = 0;
    while (l < 32 && (uint64_t(1) << l) < settings.planned_passes) ++l;
    return l;
}

IntegratorMemory PtIntegrator::memory_needed(size_t pixels, bool error_estimation) {
    IntegratorMemory m{pixels * (kSumBytesPerPixel + kFilmBytesPerPixel), pixels * kSumBytesPerPixel};
    return error_estimation ? with_error_estimation(m, pixels) : m;
}

std::vector<std::string> PtIntegrator::warnings(const Scene& scene, const SceneFeatures& features) {
    // Roughness below 0.01 is where kernels/bsdf.cl makes the lobe a delta.
    bool smooth = false;
    for (const dev::Material& m : scene.materials)
        smooth = smooth || (m.roughness < 0.01f && (m.metallic > 0.f || m.transmission > 0.f));
    if (!smooth || !(features.point_lights || features.spot_lights || features.directional_lights)) return {};
    return {"the path tracer cannot find caustics of point, spot or directional lights through glass or mirrors: that "
            "light is missing from its image and from its error estimate (--integrator sppm finds it)"};
}

bool PtIntegrator::sobol_passes() const { return settings_.sampler != Sampler::Independent; }

void PtIntegrator::prepare() { allocate_sum(); }

uint64_t PtIntegrator::max_batch() {
    static const uint64_t cap = [] {
        const char* e = std::getenv("CLPPM_PASS_BATCH");
        return e && *e ? std::clamp<uint64_t>(std::strtoull(e, nullptr, 10), 1, kMaxBatch) : kMaxBatch;
    }();
    return cap;
}

// Each pixel's sample depends on (seed, pass, pixel) alone and the kernel adds a batch's samples in
// pass order, so the batch size, chosen here from the time a pass took, never changes the image.
void PtIntegrator::run_pass() {
    const uint64_t passes = passes_batchable() ? std::min(batch_, pass_allowance_) : 1;
    const auto start = std::chrono::steady_clock::now();
    const PixelRanges ranges = begin_pass();
    if (ranges.count > 0) {
        set_args(k_trace_, scene_.set_scene_args(k_trace_), scene_.camera_buf, cl_ulong(settings_.seed),
                 cl_ulong(stats_.passes + 1), cl_uint(passes), cl_uint(ranges.first + ranges.count),
                 cl_uint(screen_log2_), accum_);
        cl::Event ev;
        enqueue_1d_range(dc_.queue, k_trace_, ranges.first, ranges.count, &ev);
        add_event_time(stats_, "path_trace", ev);
    }
    collect_event_times(stats_); // waits for the pass
    const double per_pass =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / double(passes);
    batch_ = per_pass > 0 ? uint64_t(std::clamp(kLaunchSeconds / per_pass, 1.0, double(max_batch()))) : 1;
    stats_.pass_launches += 1;
    end_pass(ranges, passes);
}

void PtIntegrator::save(Checkpoint& ck) {
    IntegratorBase::save(ck);
    if (screen_log2_ != SOBOL_PER_PIXEL) ck.header["zsobol_log2_passes"] = screen_log2_;
    save_sum(ck);
}

void PtIntegrator::restore(const Checkpoint& ck) {
    IntegratorBase::restore(ck);
    require_checkpoint_field(ck, stats_.photons_emitted == 0, "photons_emitted (a path tracer emits none)");
    // A zsobol render goes on in the layout it was planned with: its passes so far are blocks of it.
    if (screen_log2_ != SOBOL_PER_PIXEL) {
        const Json& h = ck.header;
        require_checkpoint_field(ck,
                                 h.contains("zsobol_log2_passes") && h["zsobol_log2_passes"].is_number_unsigned() &&
                                     h["zsobol_log2_passes"].get<uint64_t>() <= 32,
                                 "zsobol_log2_passes" + (h.contains("zsobol_log2_passes")
                                                             ? " = " + h["zsobol_log2_passes"].dump()
                                                             : std::string(" (missing)")));
        screen_log2_ = h["zsobol_log2_passes"].get<uint32_t>();
    }
    restore_sum(ck);
}

} // namespace clppm
