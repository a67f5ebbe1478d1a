#include "render/standard_observers.h"

#include "device/cluster.h"
#include "render/live_view_observer.h"
#include "render/mpi_stats_observer.h"
#include "render/progress_observer.h"
#include "render/save_observers.h"
#include "render/tev_observer.h"

namespace clppm {

std::vector<std::unique_ptr<RenderObserver>> standard_observers(const RenderOptions& o, RenderLog& log) {
    std::vector<std::unique_ptr<RenderObserver>> observers;
    if (cluster().rank() == 0) {
        observers.push_back(std::make_unique<ProgressObserver>(o.quiet));
        if (o.progressive_output > 0 && !o.output.empty())
            observers.push_back(std::make_unique<ProgressiveOutputObserver>(o.progressive_output));
        if (!o.display_server.empty()) observers.push_back(std::make_unique<TevObserver>(o.display_server, o.output));
        if (!o.serve.empty()) observers.push_back(std::make_unique<LiveViewObserver>(o.serve, o.tone, log));
        if (!o.checkpoint.empty())
            observers.push_back(std::make_unique<CheckpointObserver>(o.checkpoint_every, o.checkpoint_interval));
    }
    if (cluster().distributed()) observers.push_back(std::make_unique<MpiStatsObserver>());
    return observers;
}

} // namespace clppm
