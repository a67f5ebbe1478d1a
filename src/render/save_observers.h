// Observers that save while a render runs, so that nothing rendered is lost: --checkpoint's
// progressive state (every K passes, every T seconds of rendering, and at the end, interrupted or
// not) and --progressive-output's images every K passes. Both write atomically.
#pragma once
#include <cstdint>

#include "render/render_observer.h"

namespace clppm {

class CheckpointObserver : public RenderObserver {
public:
    CheckpointObserver(uint64_t every, double interval_s) : every_(every), interval_s_(interval_s) {}
    void pass_done(RenderJob& job) override;
    void finished(RenderJob& job, const RenderEnd& end) override;

private:
    uint64_t every_;
    double interval_s_;
    double last_s_ = 0;
};

class ProgressiveOutputObserver : public RenderObserver {
public:
    explicit ProgressiveOutputObserver(uint64_t every) : every_(every) {}
    void pass_done(RenderJob& job) override;

private:
    uint64_t every_;
};

} // namespace clppm
