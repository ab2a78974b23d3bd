#include "mesh/cancel.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <string>

namespace glint {

namespace {
// note: std::atomic<int> is lock-free on every target glint builds for (static_assert
// below), which is what makes request_cancel() safe inside a signal handler.
std::atomic<int> g_cancel_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "cancellation flag must be lock-free");
}  // namespace

void request_cancel(int signal) noexcept { g_cancel_signal.store(signal == 0 ? -1 : signal); }

bool cancel_requested() noexcept { return g_cancel_signal.load(std::memory_order_relaxed) != 0; }

int cancel_signal() noexcept { return std::max(0, g_cancel_signal.load()); }

void reset_cancel() noexcept { g_cancel_signal.store(0); }

void throw_if_cancelled() {
    const int s = g_cancel_signal.load(std::memory_order_relaxed);
    if (s == 0) return;
    const std::string name = s == SIGINT ? "SIGINT" : s == SIGTERM ? "SIGTERM" : "cancellation";
    throw Cancelled(name + " received: stopped, staged outputs removed, nothing half-written left");
}

}  // namespace glint
