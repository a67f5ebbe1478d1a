#include "render/mpi_stats_observer.h"

#include "device/cluster.h"
#include "util/cancellation.h"

namespace clppm {

void MpiStatsObserver::finished(RenderJob& job, const RenderEnd& end) {
    Cluster& cl = cluster();
    if (!cl.distributed()) return;
    const IntegratorStats& st = job.stats();
    const bool pixels = job.integrator().unit == WorkUnit::Pixels;
    mpi_ = {{"ranks", cl.size()}};
    if (!end.interrupted) {
        try {
            const double s = end.render_seconds;
            const std::vector<double> work = cl.all_values(s > 0 ? double(st.local_work) / s : 0.0);
            const std::vector<double> comm = cl.all_values(cl.communication_seconds());
            mpi_[pixels ? "samples_per_second" : "photons_per_second"] = work;
            mpi_["communication_seconds"] = comm;
        } catch (const PassCancelled&) { // a stop request while the ranks compared notes
        }
    }
    mpi_["bytes_per_pass"] = st.passes ? double(cl.communication_bytes()) / double(st.passes) : 0.0;
    mpi_["last_pass_share"] = st.rank_photons;
}

void MpiStatsObserver::add_stats(Json& stats) const {
    if (!mpi_.is_null()) stats["mpi"] = mpi_;
}

} // namespace clppm
