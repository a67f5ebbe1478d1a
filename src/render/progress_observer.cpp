#include "render/progress_observer.h"

namespace clppm {

void start_progress(std::optional<Progress>& progress, const RenderJob& job, bool quiet) {
    // --passes counts from the start of the original render (a total), --time this run only.
    progress.emplace(quiet, job.pass_limit(), job.options().time_limit);
    if (job.resumed_at() > 0) progress->set_resumed(job.resumed_at());
}

void update_progress(Progress& progress, const RenderJob& job) {
    if (job.estimating()) progress.set_error(job.error_measure(), job.options().target_error, job.error_eta());
    const IntegratorStats& st = job.stats();
    progress.update(st.passes, st.photons_emitted, st.mean_radius, job.render_seconds());
}

ProgressInfo progress_now(const Progress& progress, const RenderJob& job) {
    const IntegratorStats& st = job.stats();
    return progress.snapshot(st.passes, st.photons_emitted, st.mean_radius, job.render_seconds());
}

void ProgressObserver::started(RenderJob& job) { start_progress(progress_, job, quiet_); }

void ProgressObserver::pass_done(RenderJob& job) { update_progress(*progress_, job); }

void ProgressObserver::finished(RenderJob& job, const RenderEnd& end) {
    const IntegratorStats& st = job.stats();
    progress_->finish(st.passes, st.photons_emitted, st.mean_radius, end.render_seconds);
}

} // namespace clppm
