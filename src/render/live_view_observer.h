// --serve as an observer of the loop: the live view (render/live_view.h) is bound before the scene
// loads, so that a bad address fails before any work; after each pass it gets the image while a
// page watches, and its Save and Stop buttons act at pass boundaries.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "render/live_view.h"
#include "render/progress.h"
#include "render/render_log.h"
#include "render/render_observer.h"

namespace clppm {

class LiveViewObserver : public RenderObserver {
public:
    // Binds [ADDR:]PORT and says where the page is; throws Error naming --serve when it cannot.
    LiveViewObserver(const std::string& serve, const ToneMapping& tone, RenderLog& log);
    void started(RenderJob& job) override;
    void pass_done(RenderJob& job) override;
    bool wants_stop() const override { return live_->stop_requested(); }
    void finished(RenderJob& job, const RenderEnd& end) override;
    void add_stats(Json& stats) const override;

    const LiveView& live_view() const { return *live_; }

private:
    void publish(const RenderJob& job);

    std::unique_ptr<LiveView> live_;
    std::optional<Progress> progress_; // the page's progress, as the progress line has it
    bool stopped_it_ = false;
};

} // namespace clppm
