// What watches or saves a render as it runs (Cycles' display and output drivers, Blender's
// RenderEngine seen from the other side): the progress line, the live view, tev, checkpoints,
// progressive outputs, the MPI statistics. The loop (render/render_loop.h) tells each what
// happened; none of them changes the image.
#pragma once
#include "io/stats_json.h"
#include "render/render_job.h"

namespace clppm {

class RenderObserver {
public:
    virtual ~RenderObserver() = default;
    // Before the first pass of this run.
    virtual void started(RenderJob&) {}
    // After each complete pass.
    virtual void pass_done(RenderJob&) {}
    // A request to end the render after the current pass (the live view's Stop).
    virtual bool wants_stop() const { return false; }
    // The run is over (`end` says how); every rank calls it, so a collective may run here.
    virtual void finished(RenderJob&, const RenderEnd&) {}
    // What the observer adds to --stats-json, after finished().
    virtual void add_stats(Json&) const {}
};

} // namespace clppm
