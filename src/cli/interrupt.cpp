#include "cli/interrupt.h"

#include <csignal>
#include <unistd.h>

#include "util/cancellation.h"

namespace clppm {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int sig) {
    if (g_signal != 0) _exit(128 + sig); // the second signal: leave now
    g_signal = sig;
    request_cancel(); // the pass in progress stops at its next photon batch
    static const char msg[] =
        "\nclppm: stopping: the last complete pass is kept (press Ctrl-C again to quit at once)\n";
    ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
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

} // namespace clppm
