#include "util/cancellation.h"

#include <atomic>

namespace clppm {

namespace {

std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

} // namespace

void request_cancel() { g_cancel.store(true, std::memory_order_relaxed); }

bool cancel_requested() { return g_cancel.load(std::memory_order_relaxed); }

void clear_cancel() { g_cancel.store(false, std::memory_order_relaxed); }

} // namespace clppm
