#include "mesh/cancel.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <mutex>
#include <string>
#include <system_error>
#include <vector>

namespace glint {

namespace {
// note: std::atomic<int> is lock-free on every target glint builds for (static_assert
// below), which is what makes request_cancel() safe inside a signal handler.
std::atomic<int> g_cancel_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "cancellation flag must be lock-free");

// note: allocated once and never destroyed, so the watchdog thread may still use it while the
// main thread runs static destructors on its way out.
struct StagedList {
    std::mutex mutex;
    std::vector<std::filesystem::path> paths;
};
StagedList& staged_list() {
    static auto* list = new StagedList;
    return *list;
}
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

void track_staged(const std::filesystem::path& path) {
    StagedList& list = staged_list();
    const std::lock_guard lock(list.mutex);
    list.paths.push_back(path);
}

void untrack_staged(const std::filesystem::path& path) noexcept {
    StagedList& list = staged_list();
    const std::lock_guard lock(list.mutex);
    std::erase(list.paths, path);
}

std::size_t remove_staged_now() noexcept {
    StagedList& list = staged_list();
    const std::lock_guard lock(list.mutex);
    std::size_t removed = 0;
    for (const auto& path : list.paths) {
        std::error_code ec;
        if (std::filesystem::remove_all(path, ec) > 0 && !ec) ++removed;
    }
    list.paths.clear();
    return removed;
}

}  // namespace glint
