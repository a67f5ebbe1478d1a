// The MPI statistics of a render on several processes (device/cluster.h), for --stats-json: each
// rank's speed and time in communication (a collective at the end, on every rank, unless the
// render was interrupted: a rank may be gone), the bytes a pass sends and the last pass's shares.
#pragma once
#include "render/render_observer.h"

namespace clppm {

class MpiStatsObserver : public RenderObserver {
public:
    void finished(RenderJob& job, const RenderEnd& end) override;
    void add_stats(Json& stats) const override;

private:
    Json mpi_;
};

} // namespace clppm
