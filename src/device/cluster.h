// One render on several processes (issue 18): `mpirun -np N clppm ...`. Every rank loads the scene
// and runs the same deterministic work (eye pass, radius updates, error statistics); what differs
// is only which photons (integrators/photon_passes.h) or pixels (integrators/pt_integrator.h) a
// rank traces, and the ranks then combine their results exactly: integer flux sums added by an
// MPI reduction (integer addition is associative, so the sum is the same in any order and equals
// one process's), and the path tracer's per-pixel sums gathered from the rank that computed them.
// Every rank therefore holds the whole state after each pass; rank 0 writes the outputs.
//
// MPI is process-wide, and so is this: cluster() is the one instance, started by ClusterSession in
// main. Built without MPI (CLPPM_HAVE_MPI undefined), or not started by an MPI launcher, it is a
// cluster of one whose collectives return at once.
//
// The collectives poll for cancellation (util/cancellation.h): a rank asked to stop (mpirun turns
// Ctrl-C into SIGTERM for every rank, and kills them a second later) abandons the pass it is in
// instead of waiting for ranks that may be gone, throwing PassCancelled; its state is then that of
// the last complete pass, which rank 0 writes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace clppm {

class Cluster {
public:
    int rank() const { return rank_; }
    int size() const { return size_; }
    bool distributed() const { return size_ > 1; }
    // "rank 2: " on ranks other than 0 when distributed, "" otherwise: for messages.
    std::string prefix() const;

    // data[i] = the sum over ranks of data[i], on every rank (exact: integer addition).
    void sum(int64_t* data, size_t n);
    // Every rank's `value`, in rank order, on every rank.
    std::vector<double> all_values(double value);
    // Every rank's `values` (the same count on each), rank after rank, on every rank.
    std::vector<double> all_values(const std::vector<double>& values);
    // Rank 0's `value` on every rank.
    bool from_rank0(bool value);
    // Rank r's doubles data[first[r] .. first[r] + count[r]), on every rank, in place; `first` and
    // `count` are the same on every rank.
    void share_slices(double* data, const std::vector<size_t>& first, const std::vector<size_t>& count);

    // Seconds spent in collectives and bytes this rank sent to them, so far.
    double communication_seconds() const { return comm_seconds_; }
    uint64_t communication_bytes() const { return comm_bytes_; }
    // Whether a collective was abandoned (cancelled): MPI cannot then be finalised cleanly.
    bool abandoned() const { return abandoned_; }

private:
    friend class ClusterSession;
    int rank_ = 0, size_ = 1;
    double comm_seconds_ = 0;
    uint64_t comm_bytes_ = 0;
    bool abandoned_ = false;
};

Cluster& cluster();

// Started from main: MPI_Init when an MPI launcher started this process (its environment says
// so), MPI_Finalize at the end. A build without MPI started by a launcher with several processes
// throws clppm::Error: it would render the whole image once per process.
class ClusterSession {
public:
    ClusterSession(int* argc, char*** argv);
    ~ClusterSession();
    ClusterSession(const ClusterSession&) = delete;
    ClusterSession& operator=(const ClusterSession&) = delete;

private:
    bool started_ = false;
};

// The number of processes an MPI launcher says it started (Open MPI, MPICH's Hydra, Slurm's PMI), from
// the environment; 0 when none did. `getenv` is the lookup (a parameter for tests).
int launcher_process_count(const char* (*getenv)(const char*));

// Whether this build can distribute a render (it was built with MPI).
bool built_with_mpi();

} // namespace clppm
