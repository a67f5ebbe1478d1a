#include "device/cluster.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <string>
#include <thread>

#ifdef CLPPM_HAVE_MPI
#include <mpi.h>
#endif

#include "util/cancellation.h"
#include "util/error.h"
#include "util/steady_seconds.h"

namespace clppm {

namespace {

Cluster g_cluster;

const char* std_getenv(const char* name) { return std::getenv(name); }

} // namespace

Cluster& cluster() { return g_cluster; }

bool built_with_mpi() {
#ifdef CLPPM_HAVE_MPI
    return true;
#else
    return false;
#endif
}

int launcher_process_count(const char* (*getenv)(const char*)) {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) { // Open MPI; MPICH (Hydra), Slurm PMI
        const char* v = getenv(name);
        if (v && *v) {
            char* end = nullptr;
            const long n = std::strtol(v, &end, 10);
            if (*end == '\0' && n > 0) return int(n);
        }
    }
    return 0;
}

std::string Cluster::prefix() const {
    return distributed() && rank_ != 0 ? "rank " + std::to_string(rank_) + ": " : "";
}

#ifdef CLPPM_HAVE_MPI

namespace {

// Waits for a non-blocking collective, polling for cancellation: a rank asked to stop does not
// wait for ranks that may be gone (the request is abandoned; MPI is not finalised then).
void wait(MPI_Request* req, Cluster& c, bool* abandoned) {
    int done = 0;
    for (int spins = 0;; ++spins) {
        MPI_Test(req, &done, MPI_STATUS_IGNORE);
        if (done) return;
        if (cancel_requested()) {
            *abandoned = true;
            throw PassCancelled();
        }
        // Other ranks may share this machine's cores: sleep rather than spin once it takes a while.
        if (spins > 100) std::this_thread::sleep_for(std::chrono::microseconds(spins > 1000 ? 1000 : 50));
    }
    (void)c;
}

} // namespace

void Cluster::sum(int64_t* data, size_t n) {
    if (size_ == 1 || n == 0) return;
    const double t0 = steady_seconds();
    MPI_Request req;
    // In chunks of at most 2^30 values: MPI counts are int.
    for (size_t at = 0; at < n; at += size_t(1) << 30) {
        const int count = int(std::min(n - at, size_t(1) << 30));
        MPI_Iallreduce(MPI_IN_PLACE, data + at, count, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD, &req);
        wait(&req, *this, &abandoned_);
    }
    comm_bytes_ += n * sizeof(int64_t);
    comm_seconds_ += steady_seconds() - t0;
}

std::vector<double> Cluster::all_values(double value) { return all_values(std::vector<double>{value}); }

std::vector<double> Cluster::all_values(const std::vector<double>& values) {
    if (size_ == 1) return values;
    std::vector<double> all(values.size() * static_cast<size_t>(size_));
    const double t0 = steady_seconds();
    MPI_Request req;
    MPI_Iallgather(values.data(), int(values.size()), MPI_DOUBLE, all.data(), int(values.size()), MPI_DOUBLE,
                   MPI_COMM_WORLD, &req);
    wait(&req, *this, &abandoned_);
    comm_bytes_ += values.size() * sizeof(double);
    comm_seconds_ += steady_seconds() - t0;
    return all;
}

bool Cluster::from_rank0(bool value) {
    if (size_ == 1) return value;
    const double t0 = steady_seconds();
    int v = value ? 1 : 0;
    MPI_Request req;
    MPI_Ibcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD, &req);
    wait(&req, *this, &abandoned_);
    comm_bytes_ += sizeof(int);
    comm_seconds_ += steady_seconds() - t0;
    return v != 0;
}

void Cluster::share_slices(double* data, const std::vector<size_t>& first, const std::vector<size_t>& count) {
    if (size_ == 1) return;
    if (first.size() != size_t(size_) || count.size() != size_t(size_))
        throw Error("share_slices: one slice per rank expected");
    const size_t ranks = static_cast<size_t>(size_);
    std::vector<int> displs(ranks), counts(ranks);
    for (int r = 0; r < size_; ++r) {
        if (first[r] + count[r] > size_t(1) << 31 || count[r] >= size_t(1) << 31)
            throw Error("share_slices: a slice beyond MPI's int counts (2^31 values)");
        displs[r] = int(first[r]);
        counts[r] = int(count[r]);
    }
    const double t0 = steady_seconds();
    MPI_Request req;
    MPI_Iallgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, counts.data(), displs.data(), MPI_DOUBLE, MPI_COMM_WORLD,
                    &req);
    wait(&req, *this, &abandoned_);
    comm_bytes_ += count[size_t(rank_)] * sizeof(double);
    comm_seconds_ += steady_seconds() - t0;
}

ClusterSession::ClusterSession(int* argc, char*** argv) {
    if (launcher_process_count(std_getenv) == 0) return; // not started by mpirun: a cluster of one
    int provided = 0;
    // Only the main thread calls MPI (the photon passes' device threads do not).
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    started_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &g_cluster.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &g_cluster.size_);
}

ClusterSession::~ClusterSession() {
    // MPI_Finalize waits for every rank. After an abandoned collective, or on the way out with an
    // error that other ranks may not share (they would be waiting in a collective), it would wait
    // for ever: leave without, and mpirun ends the job, saying which rank left.
    // The same after a stop request (Ctrl-C, or mpirun's SIGTERM when a rank died): the other
    // ranks may be gone.
    if (started_ && !g_cluster.abandoned_ && !cancel_requested() && std::uncaught_exceptions() == 0) MPI_Finalize();
}

#else // without MPI: a cluster of one

void Cluster::sum(int64_t*, size_t) {}
std::vector<double> Cluster::all_values(double value) { return {value}; }
std::vector<double> Cluster::all_values(const std::vector<double>& values) { return values; }
bool Cluster::from_rank0(bool value) { return value; }
void Cluster::share_slices(double*, const std::vector<size_t>&, const std::vector<size_t>&) {}

ClusterSession::ClusterSession(int*, char***) {
    const int n = launcher_process_count(std_getenv);
    if (n > 1)
        throw Error("this clppm was built without MPI, and an MPI launcher started " + std::to_string(n) +
                    " copies of it: each would render the whole image. Install libopenmpi-dev and rebuild "
                    "(scripts/install-deps.sh), or run one process");
}

ClusterSession::~ClusterSession() = default;

#endif

} // namespace clppm
