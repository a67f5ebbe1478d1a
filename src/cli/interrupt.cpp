#include "cli/interrupt.h"

#include <csignal>
#include <unistd.h>

#include "util/cancellation.h"

namespace clppm {

namespace {

volatile std::sig_atomic_t g_signal = 0;
volatile std::sig_atomic_t g_context = 0; // 0: one process; 1: rank 0 of several; 2: another rank

extern "C" void on_signal(int sig) {
    if (g_signal != 0) _exit(128 + sig); // the second signal: leave now
    g_signal = sig;
    request_cancel(); // the pass in progress stops at its next photon batch
    static const char one[] =
        "\nclppm: stopping: the last complete pass is kept (press Ctrl-C again to quit at once)\n";
    // mpirun sends SIGTERM to every rank on Ctrl-C, and when a rank has died or failed (it names
    // that rank itself); it kills them all a second later.
    static const char several[] =
        "\nclppm: stopping: the MPI job is ending (Ctrl-C on mpirun, or a process that died or failed: "
        "mpirun names it); writing the last complete pass\n";
    ssize_t ignored = 0;
    if (g_context == 0) ignored = write(STDERR_FILENO, one, sizeof one - 1);
    else if (g_context == 1) ignored = write(STDERR_FILENO, several, sizeof several - 1);
    (void)ignored;
}

} // namespace

void install_interrupt_handlers() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

int interrupt_signal() { return int(g_signal); }

void set_interrupt_context(int ranks, int rank) { g_context = ranks <= 1 ? 0 : rank == 0 ? 1 : 2; }

} // namespace clppm
