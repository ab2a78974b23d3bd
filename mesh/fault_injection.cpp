#include "mesh/fault_injection.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace glint {

namespace {

struct Fault {
    std::string point;
    long nth = 1;
    std::string action;
    long seen = 0;
};

// The faults GLINT_FAULT asks for; malformed entries are ignored (this is a test hook, never
// a user's option).
std::vector<Fault> parse_faults(const char* text) {
    std::vector<Fault> faults;
    std::string all = text;
    std::size_t start = 0;
    while (start <= all.size()) {
        const std::size_t comma = std::min(all.find(',', start), all.size());
        const std::string entry = all.substr(start, comma - start);
        start = comma + 1;
        const std::size_t colon = entry.rfind(':');
        if (colon == std::string::npos) continue;
        Fault f;
        f.point = entry.substr(0, colon);
        f.action = entry.substr(colon + 1);
        if (const std::size_t hash = f.point.find('#'); hash != std::string::npos) {
            f.nth = std::strtol(f.point.c_str() + hash + 1, nullptr, 10);
            f.point.resize(hash);
        }
        if (f.nth >= 1) faults.push_back(std::move(f));
    }
    return faults;
}

struct Faults {
    std::mutex mutex;
    std::vector<Fault> list;
};

// note: read once; null when GLINT_FAULT is unset, which keeps fault_point() to one load.
std::atomic<Faults*> g_faults{nullptr};
std::once_flag g_read;

void act(const std::string& action) {
    if (action == "term") std::raise(SIGTERM);
    else if (action == "int") std::raise(SIGINT);
    else if (action == "kill") std::raise(SIGKILL);
    else if (action == "stall") std::this_thread::sleep_for(std::chrono::seconds(30));
    else if (action == "pause") std::this_thread::sleep_for(std::chrono::seconds(2));
}

}  // namespace

void fault_point(std::string_view point) {
    std::call_once(g_read, [] {
        if (const char* text = std::getenv("GLINT_FAULT"); text != nullptr && *text != '\0')
            g_faults.store(new Faults{{}, parse_faults(text)});
    });
    Faults* faults = g_faults.load(std::memory_order_relaxed);
    if (faults == nullptr) return;
    std::string action;
    {
        const std::lock_guard lock(faults->mutex);
        for (Fault& f : faults->list)
            if (f.point == point && ++f.seen == f.nth) action = f.action;
    }
    if (!action.empty()) act(action);
}

}  // namespace glint
