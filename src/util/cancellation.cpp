#include "util/cancellation.h"

namespace clppm {

namespace {

std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

thread_local const CancelToken* t_token = nullptr;

} // namespace

void request_cancel() { g_cancel.store(true, std::memory_order_relaxed); }

void clear_cancel() { g_cancel.store(false, std::memory_order_relaxed); }

CancelScope::CancelScope(const CancelToken* token) : previous_(t_token) { t_token = token; }

CancelScope::~CancelScope() { t_token = previous_; }

const CancelToken* current_cancel_token() { return t_token; }

bool cancel_requested() { return g_cancel.load(std::memory_order_relaxed) || (t_token && t_token->requested()); }

} // namespace clppm
