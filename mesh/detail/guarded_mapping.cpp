#include "mesh/detail/guarded_mapping.h"

#include "mesh/error.h"

#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>

namespace glint::detail {

namespace {

// The guarded ranges, read by the signal handler: lock-free atomics only.
struct Slot {
    std::atomic<std::uintptr_t> begin{0};  // 0: free
    std::atomic<std::size_t> size{0};
    std::atomic<bool> shrank{false};
};
constexpr int kSlots = 32;
std::array<Slot, kSlots> g_slots;
std::uintptr_t g_page = 4096;

std::atomic<std::size_t> g_map_above{std::size_t{2} << 30};

std::mutex g_install_mutex;  // guards what follows (never taken by the handler)
int g_live = 0;
struct sigaction g_previous {};

// note: mmap is not on POSIX's list of async-signal-safe functions, but on Linux it is a plain
// system call that takes no lock of the C library; it is the usual way to serve such a fault.
void on_sigbus(int signal, siginfo_t* info, void* context) {
    const auto address = reinterpret_cast<std::uintptr_t>(info->si_addr);
    for (Slot& slot : g_slots) {
        const std::uintptr_t begin = slot.begin.load(std::memory_order_acquire);
        const std::size_t size = slot.size.load(std::memory_order_acquire);
        if (begin == 0 || address < begin || address >= begin + size) continue;
        const std::uintptr_t page = address & ~(g_page - 1);
        void* zeros = ::mmap(reinterpret_cast<void*>(page), begin + size - page, PROT_READ,
                             MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0);
        if (zeros == MAP_FAILED) break;
        slot.shrank.store(true, std::memory_order_release);
        return;  // the faulting read runs again and reads zeros
    }
    if ((g_previous.sa_flags & SA_SIGINFO) != 0 && g_previous.sa_sigaction != nullptr) {
        g_previous.sa_sigaction(signal, info, context);
    } else if (g_previous.sa_handler != SIG_DFL && g_previous.sa_handler != SIG_IGN) {
        g_previous.sa_handler(signal);
    } else {
        // The default: put it back and return; the fault happens again and ends the process
        // with SIGBUS as it would have without us.
        struct sigaction fallback {};
        fallback.sa_handler = SIG_DFL;
        ::sigaction(SIGBUS, &fallback, nullptr);
    }
}

void install() {
    std::lock_guard lock(g_install_mutex);
    if (g_live++ > 0) return;
    g_page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    struct sigaction ours {};
    ours.sa_sigaction = on_sigbus;
    ours.sa_flags = SA_SIGINFO | SA_ONSTACK;
    sigemptyset(&ours.sa_mask);
    ::sigaction(SIGBUS, &ours, &g_previous);
}

void uninstall() {
    std::lock_guard lock(g_install_mutex);
    if (--g_live > 0) return;
    struct sigaction current {};
    ::sigaction(SIGBUS, nullptr, &current);
    // Someone who installed a handler after us keeps theirs.
    if ((current.sa_flags & SA_SIGINFO) != 0 && current.sa_sigaction == on_sigbus)
        ::sigaction(SIGBUS, &g_previous, nullptr);
}

}  // namespace

std::size_t map_above_bytes() noexcept { return g_map_above.load(); }
void set_map_above_bytes_for_testing(std::size_t bytes) noexcept { g_map_above.store(bytes); }

GuardedMapping::GuardedMapping(int fd, std::size_t size) : size_(size) {
    data_ = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (data_ == MAP_FAILED) {
        data_ = nullptr;
        throw IoError(std::string("cannot map: ") + std::strerror(errno));
    }
    for (int i = 0; i < kSlots && slot_ < 0; ++i) {
        std::uintptr_t expected = 0;
        if (g_slots[static_cast<std::size_t>(i)].begin.compare_exchange_strong(
                expected, ~std::uintptr_t{0}))  // claimed; published below
            slot_ = i;
    }
    if (slot_ < 0) {
        ::munmap(data_, size_);
        throw IoError("cannot map: more than " + std::to_string(kSlots) +
                      " large files are open at once");
    }
    Slot& slot = g_slots[static_cast<std::size_t>(slot_)];
    slot.shrank.store(false, std::memory_order_relaxed);
    slot.size.store(size_, std::memory_order_release);
    slot.begin.store(reinterpret_cast<std::uintptr_t>(data_), std::memory_order_release);
    install();
}

GuardedMapping::~GuardedMapping() {
    uninstall();
    Slot& slot = g_slots[static_cast<std::size_t>(slot_)];
    slot.begin.store(0, std::memory_order_release);
    slot.size.store(0, std::memory_order_release);
    ::munmap(data_, size_);
}

std::span<const char> GuardedMapping::bytes() const {
    return {static_cast<const char*>(data_), size_};
}

bool GuardedMapping::shrank() const noexcept {
    return g_slots[static_cast<std::size_t>(slot_)].shrank.load(std::memory_order_acquire);
}

}  // namespace glint::detail
