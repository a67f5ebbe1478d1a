#include "render/save_observers.h"

namespace clppm {

void CheckpointObserver::pass_done(RenderJob& job) {
    const double now = job.render_seconds();
    if ((every_ > 0 && job.passes() % every_ == 0) || now - last_s_ >= interval_s_) {
        job.save_checkpoint();
        last_s_ = now;
    }
}

// A checkpoint of zero passes would replace an earlier one with nothing.
void CheckpointObserver::finished(RenderJob& job, const RenderEnd&) {
    if (job.passes() > 0) job.save_checkpoint();
}

void ProgressiveOutputObserver::pass_done(RenderJob& job) {
    if (job.passes() % every_ == 0) job.save_images(job.options().output, job.options().write_png);
}

} // namespace clppm
