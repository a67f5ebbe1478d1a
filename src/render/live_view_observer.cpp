#include "render/live_view_observer.h"

#include <cstdio>

#include "render/progress_observer.h"

namespace clppm {

LiveViewObserver::LiveViewObserver(const std::string& serve, const ToneMapping& tone, RenderLog& log) {
    const ServeAddress address = parse_serve_address(serve);
    live_ = std::make_unique<LiveView>(address, tone);
    std::fprintf(stderr, "clppm: live view at %s\n", live_->url().c_str());
    if (!is_loopback(address.host))
        log.warn("--serve " + serve + ": anyone who can reach this address can watch and stop the render");
}

void LiveViewObserver::started(RenderJob& job) { start_progress(progress_, job, true); }

// The film (a readback, which changes nothing), the error map and the progress.
void LiveViewObserver::publish(const RenderJob& job) {
    const ProgressInfo p = progress_now(*progress_, job);
    const RenderOptions& opt = job.options();
    const nlohmann::json j = {{"pass", p.pass},
                              {"pass_limit", p.pass_limit},
                              {"time_limit", p.time_limit},
                              {"photons", p.photons},
                              {"radius", p.radius},
                              {"elapsed_s", p.elapsed_s},
                              {"passes_per_second", progress_rate(p)},
                              {"eta_s", progress_eta(p)},
                              {"error", job.estimating() ? job.error_measure() : -1.0},
                              {"target_error", opt.target_error},
                              {"integrator", job.integrator().name}};
    static const std::vector<float> none;
    live_->publish(job.image(), job.estimating() ? job.error().relative : none,
                   opt.target_error > 0 ? 2 * opt.target_error : 0.2, j);
}

void LiveViewObserver::pass_done(RenderJob& job) {
    update_progress(*progress_, job);
    if (live_->due()) publish(job);
    if (live_->take_save_request()) {
        if (job.options().output.empty()) {
            job.log().warn("the live view asked to save, but this render has no output file");
            return;
        }
        job.save_outputs();
        job.log().note("saved " + job.options().output + " at pass " + std::to_string(job.passes()) +
                       " (asked by the live view)");
    }
}

void LiveViewObserver::finished(RenderJob& job, const RenderEnd& end) {
    stopped_it_ = end.stopped_by_viewer;
    // The final image, for whoever still watches while the outputs are written.
    if (job.passes() > 0) publish(job);
    live_->set_state(end.interrupted ? "interrupted" : "finished");
}

void LiveViewObserver::add_stats(Json& stats) const {
    stats["live_view"] = {{"url", live_->url()}, {"requests", live_->requests()}, {"stopped_it", stopped_it_}};
}

} // namespace clppm
