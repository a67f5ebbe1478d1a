// A request to stop the work in progress (Ctrl-C, SIGTERM), raised from a signal handler and read
// by the long loops below the command line: a pass's photon batches check it and abandon their
// pass by throwing PassCancelled, so that a render stops within one batch, keeping the state of
// its last complete pass.
#pragma once
#include <exception>

namespace clppm {

// Async-signal-safe (a lock-free atomic store).
void request_cancel();
bool cancel_requested();
// Withdraws the request, once it has been answered: a library's caller (the Python module) renders
// again after an interrupted render. The command line never withdraws one.
void clear_cancel();

struct PassCancelled : std::exception {
    const char* what() const noexcept override { return "the pass was cancelled"; }
};

// Throws PassCancelled when a stop was requested.
inline void throw_if_cancelled() {
    if (cancel_requested()) throw PassCancelled();
}

} // namespace clppm
