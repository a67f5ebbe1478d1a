// Requests to stop the work in progress, read by the long loops below the front ends: a pass's
// photon batches check them and abandon their pass by throwing PassCancelled, so that a render
// stops within one batch, keeping the state of its last complete pass. Two kinds:
//   - the process's (Ctrl-C, SIGTERM), raised from a signal handler: every render in the process
//     stops;
//   - a render's own (CancelToken: the Python module's Renderer.cancel(), from any thread), seen by
//     the thread that runs the render's passes while a CancelScope names the token there, and by
//     the threads that thread starts for the pass (integrators/device_fan_out.cpp). Other renders
//     in the process go on.
#pragma once
#include <atomic>
#include <exception>

namespace clppm {

// The process's request. Async-signal-safe (a lock-free atomic store).
void request_cancel();
// Withdraws it, once it has been answered: a library's caller (the Python module) renders again
// after an interrupted render. The command line never withdraws one.
void clear_cancel();

// One render's request.
class CancelToken {
public:
    void request() { flag_.store(true, std::memory_order_relaxed); }
    void clear() { flag_.store(false, std::memory_order_relaxed); }
    bool requested() const { return flag_.load(std::memory_order_relaxed); }

private:
    std::atomic<bool> flag_{false};
};

// While alive, cancel_requested() on this thread answers `token`'s request as well (nullptr: none).
class CancelScope {
public:
    explicit CancelScope(const CancelToken* token);
    ~CancelScope();
    CancelScope(const CancelScope&) = delete;
    CancelScope& operator=(const CancelScope&) = delete;

private:
    const CancelToken* previous_;
};

// The token of this thread's innermost CancelScope, or nullptr: to hand on to the threads a pass
// starts.
const CancelToken* current_cancel_token();

// The process's request, or the current scope's token's.
bool cancel_requested();

struct PassCancelled : std::exception {
    const char* what() const noexcept override { return "the pass was cancelled"; }
};

// Throws PassCancelled when a stop was requested.
inline void throw_if_cancelled() {
    if (cancel_requested()) throw PassCancelled();
}

} // namespace clppm
