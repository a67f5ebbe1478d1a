#include "render/render_loop.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "device/cluster.h"
#include "io/image_io.h"
#include "util/cancellation.h"

namespace clppm {

RenderLoop::RenderLoop(RenderJob& job, std::vector<std::unique_ptr<RenderObserver>> observers)
    : job_(job), observers_(std::move(observers)) {
    policy_.pass_limit = job.pass_limit();
    policy_.time_limit = job.options().time_limit;
}

void RenderLoop::start() {
    if (started_) return;
    started_ = true;
    for (auto& o : observers_) o->started(job_);
}

bool RenderLoop::should_continue() {
    start();
    bool viewer_stop = false;
    for (const auto& o : observers_) viewer_stop = viewer_stop || o->wants_stop();
    reason_ = policy_.check(job_.passes(), job_.render_seconds(), job_.error_target_reached(), cancel_requested(),
                            viewer_stop);
    stopped_by_viewer_ = stopped_by_viewer_ || reason_ == StopReason::Viewer;
    interrupted_ = interrupted_ || reason_ == StopReason::Interrupt;
    const bool go = reason_ == StopReason::None;
    Cluster& cl = cluster();
    if (!cl.distributed()) return go;
    try {
        const bool all = cl.from_rank0(go);
        if (!all && !job_.writer()) interrupted_ = false; // rank 0 ended it (its interrupt, if any, is its own)
        if (all && cancel_requested()) interrupted_ = true;
        return all && !interrupted_;
    } catch (const PassCancelled&) { // this rank's own stop request, while waiting for rank 0
        interrupted_ = true;
        return false;
    }
}

bool RenderLoop::run_pass(uint64_t max_passes) {
    start();
    try {
        job_.run_pass(max_passes);
    } catch (const PassCancelled&) { // the statistics are those of the last complete pass
        interrupted_ = true;
        return false;
    }
    for (auto& o : observers_) o->pass_done(job_);
    return true;
}

uint64_t RenderLoop::pass_allowance() const {
    const uint64_t done = job_.passes();
    uint64_t n = std::numeric_limits<uint64_t>::max();
    if (policy_.pass_limit > 0) n = policy_.pass_limit > done ? policy_.pass_limit - done : 1;
    const RenderOptions& opt = job_.options();
    for (uint64_t every : {opt.progressive_output, opt.checkpoint_every})
        if (every > 0) n = std::min(n, every - done % every);
    return n;
}

RenderEnd RenderLoop::run() {
    while (step_batch()) {}
    return finish();
}

RenderEnd RenderLoop::finish() {
    if (finished_) return end_;
    finished_ = true;
    start();
    RenderLog& log = job_.log();
    const RenderOptions& opt = job_.options();
    end_.interrupted = interrupted_;
    end_.stopped_by_viewer = stopped_by_viewer_;
    end_.render_seconds = job_.render_seconds();
    const uint64_t passes = job_.passes();
    if (stopped_by_viewer_) log.note("stopped after pass " + std::to_string(passes) + " from the live view");
    if (interrupted_ && passes == 0) {
        // Stopped before a single pass (during the kernel build, say): an image of zero passes
        // must not replace whatever the outputs hold.
        for (auto& o : observers_) o->finished(job_, end_);
        end_.nothing_written = true;
        if (!opt.output.empty())
            log.warn("interrupted before the first pass: nothing written, " + opt.output + " left as it was");
        return end_;
    }
    // The image first: after an interrupt under mpirun, the job is killed a second later.
    Image img;
    if (job_.writer()) {
        img = job_.image(interrupted_);
        job_.save_outputs(img);
    }
    for (auto& o : observers_) o->finished(job_, end_);
    if (!job_.writer()) return end_;
    // Radiance is finite and never negative: a pixel that is not is a defect, said loudly (the
    // image is kept, so nothing rendered is lost), and the render counts as failed.
    const size_t nonfinite = count_nonfinite(img), negative = count_negative(img);
    end_.defective_pixels = nonfinite + negative;
    say_result(end_);
    if (end_.defective_pixels)
        log.error(std::to_string(nonfinite) + " pixel(s) are NaN or Inf and " + std::to_string(negative) + " negative" +
                  (opt.output.empty() ? std::string() : " in " + opt.output) + " (a renderer defect)");
    if (!opt.stats_json.empty()) {
        Json j = job_.stats_json(end_, &img);
        for (const auto& o : observers_) o->add_stats(j);
        write_stats_json(opt.stats_json, j);
    }
    std::string wrote;
    for (const std::string* f : {&opt.output, &opt.error_output, &opt.checkpoint}) {
        if (f->empty()) continue;
        wrote += (wrote.empty() ? "" : " and ") + *f;
        if (f == &opt.output && opt.write_png) wrote += " and " + png_path_for(opt.output);
    }
    if (!wrote.empty()) log.note("wrote " + wrote);
    if (interrupted_)
        log.warn("interrupted after pass " + std::to_string(passes) +
                 (opt.checkpoint.empty() ? std::string() : "; continue with --resume " + opt.checkpoint));
    return end_;
}

// The error estimate at the end, and PPM's floor when it is what kept the target out of reach.
void RenderLoop::say_result(const RenderEnd&) const {
    if (!job_.estimating()) return;
    const RenderOptions& opt = job_.options();
    const ErrorImage& e = job_.error();
    char line[300];
    std::snprintf(
        line, sizeof line, "estimated error %.4g (90th percentile of the relative error), bound %.4g (confidence %g)%s",
        e.expected_error, e.image_error, confidence_of(opt), job_.error_target_reached() ? ": reached the target" : "");
    job_.log().note(line);
    if (opt.target_error > 0 && !job_.error_target_reached() && e.sample_floor > opt.target_error &&
        e.sample_floor >= 0.8 * e.expected_error) {
        std::snprintf(line, sizeof line,
                      "--target-error %g: out of PPM's reach here; its %u fixed samples per pixel alone leave an "
                      "estimated error of %.3g (--spp more, or --integrator sppm, which samples anew every pass)",
                      opt.target_error, opt.settings.spp, e.sample_floor);
        job_.log().warn(line);
    }
}

} // namespace clppm
