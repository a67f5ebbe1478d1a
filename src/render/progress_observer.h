// The progress line (render/progress.h) as an observer of the loop: drawn after every pass, with
// the estimated error when the render estimates it, and a final line at the end.
#pragma once
#include <optional>

#include "render/progress.h"
#include "render/render_observer.h"

namespace clppm {

// What a progress line shows after the job's last pass (without the error: Progress::set_error).
ProgressInfo progress_now(const Progress& progress, const RenderJob& job);

class ProgressObserver : public RenderObserver {
public:
    explicit ProgressObserver(bool quiet) : quiet_(quiet) {}
    void started(RenderJob& job) override;
    void pass_done(RenderJob& job) override;
    void finished(RenderJob& job, const RenderEnd& end) override;

private:
    bool quiet_;
    std::optional<Progress> progress_;
};

// A progress line's state for `job`, kept current by update_progress (quiet: it draws nothing).
void start_progress(std::optional<Progress>& progress, const RenderJob& job, bool quiet);
void update_progress(Progress& progress, const RenderJob& job);

} // namespace clppm
