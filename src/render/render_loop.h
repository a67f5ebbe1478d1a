// The one render loop (SmallVCM's RunIteration, Cycles' Session): runs passes of a RenderJob
// until the stop policy says enough, tells the observers after each, and at the end writes what
// the options ask for. The command line runs it whole (run()); the Python module also steps it a
// pass at a time. With several processes (device/cluster.h) rank 0's decision to go on is every
// rank's, so that all run the same passes; rank 0 alone writes.
#pragma once
#include <memory>
#include <vector>

#include "render/render_job.h"
#include "render/render_observer.h"
#include "render/stop_policy.h"

namespace clppm {

class RenderLoop {
public:
    RenderLoop(RenderJob& job, std::vector<std::unique_ptr<RenderObserver>> observers);

    // Whether another pass should run: the stop policy, asked before every pass.
    bool should_continue();
    // One pass, then the observers. False when a stop request cancelled it: the state is then the
    // last complete pass's.
    bool run_pass(uint64_t max_passes = 1);
    // should_continue() and then run_pass().
    bool step() { return should_continue() && run_pass(); }
    // The same, with as many passes at once as the integrator takes and the observers allow
    // (pass_allowance(): the path tracer batches short passes; the image is the same).
    bool step_batch() { return should_continue() && run_pass(pass_allowance()); }
    // Ends the run: the observers' finished(), then on rank 0 the outputs, what the render says
    // of its result (the error reached, pixels that are not finite), --stats-json. Once.
    RenderEnd finish();
    // Passes until the policy stops them, then finish(). Steps may run several passes at once,
    // up to the pass limit and the next pass an observer counts (pass_allowance()).
    RenderEnd run();

    bool interrupted() const { return interrupted_; }
    // The interrupt has been answered (the Python module raised KeyboardInterrupt) and the render
    // may go on: the image no longer counts as interrupted.
    void clear_interrupt() { interrupted_ = false; }
    StopReason stop_reason() const { return reason_; }

private:
    void start();
    // The most passes the next step may run: to the pass limit and to the next pass that
    // --progressive-output or --checkpoint-every counts.
    uint64_t pass_allowance() const;
    void say_result(const RenderEnd& end) const;

    RenderJob& job_;
    std::vector<std::unique_ptr<RenderObserver>> observers_;
    StopPolicy policy_;
    bool started_ = false, finished_ = false;
    bool interrupted_ = false, stopped_by_viewer_ = false;
    StopReason reason_ = StopReason::None;
    RenderEnd end_;
};

} // namespace clppm
