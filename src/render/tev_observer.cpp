#include "render/tev_observer.h"

#include "render/live_view.h"

namespace clppm {

namespace {

std::string image_name(const std::string& output) {
    if (output.empty()) return "clppm";
    return output.substr(output.find_last_of('/') + 1);
}

} // namespace

TevObserver::TevObserver(const std::string& address, const std::string& output)
    : tev_(std::make_unique<TevClient>(address, image_name(output))) {}

void TevObserver::say(RenderJob& job) {
    const std::string w = tev_->take_warning();
    if (!w.empty()) job.log().warn(w);
}

void TevObserver::pass_done(RenderJob& job) {
    say(job);
    const double now = job.render_seconds();
    if (!tev_->connected() || now - last_send_s_ < 1.0 / LiveView::kPublishHz) return;
    tev_->send(job.image());
    last_send_s_ = now;
}

void TevObserver::finished(RenderJob& job, const RenderEnd&) {
    if (tev_->connected() && job.passes() > 0) {
        tev_->send(job.image());
        tev_->flush(kFinalFlushSeconds);
    }
    say(job);
}

} // namespace clppm
