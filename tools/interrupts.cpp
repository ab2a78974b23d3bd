// SIGINT / SIGTERM for the command line: a cooperative stop, a watchdog for steps that cannot
// stop, and one line whichever way the run ends (tools/command.h).
//
// - The handlers are installed from the executable's .preinit_array, which the dynamic loader
//   runs before any shared library's initialiser: from a few milliseconds after exec (the
//   relocations) a signal is seen, where glint's ~0.4 s of library start-up used to end with
//   the default action (exit 143, no word).
// - Before that, the launcher holds them (release_launcher_signals): no moment of a run ends it
//   without a word.
// - timeout(1), shells and batch systems deliver one request both to the process and to its
//   process group, so the same signal often arrives twice within microseconds; a repeat within
//   kRepeatWindowNs is the same request (it used to kill glint without a word or a cleanup).
// - The watchdog is a thread, woken by the handler through a semaphore (sem_post is
//   async-signal-safe): kCancelGraceSeconds after the first signal, or at once on a second
//   one given later, it removes every staged output still listed (mesh/cancel.h), prints one
//   line and ends the process. As a thread it may do what a signal handler may not (remove
//   folders), while the main thread is stuck in a library call that never polls.
#include "mesh/cancel.h"
#include "tools/command.h"

#include <pthread.h>
#include <semaphore.h>
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <thread>

namespace glint::cli {

namespace {

// note: 3 s for the cooperative stop (the next view or the next thousand file lines, then the
// staged outputs removed): a call into a library (ITK, VTK, a driver) cannot poll the flag,
// and one given a hostile input may never return. A single SIGTERM must still end glint.
constexpr unsigned kCancelGraceSeconds = 3;
// note: 1 s: a person pressing Ctrl-C again to insist takes longer; the duplicate of one
// request (process and group) arrives within microseconds, under load within milliseconds.
constexpr long long kRepeatWindowNs = 1'000'000'000;

sem_t g_wake;
std::atomic<bool> g_wake_ready{false};
std::atomic<long long> g_first_signal_ns{0};
std::atomic<bool> g_insisted{false};
std::atomic<bool> g_main_reported{false};
static_assert(std::atomic<long long>::is_always_lock_free);

long long monotonic_ns() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);  // async-signal-safe
    return static_cast<long long>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

extern "C" void on_signal(int signal) {
    const int saved_errno = errno;
    const long long now = monotonic_ns();
    long long first = 0;
    if (g_first_signal_ns.compare_exchange_strong(first, now)) {
        request_cancel(signal);
    } else if (now - first < kRepeatWindowNs) {
        errno = saved_errno;
        return;  // the same request delivered twice
    } else {
        g_insisted.store(true);
    }
    if (g_wake_ready.load()) sem_post(&g_wake);
    errno = saved_errno;
}

// A signal ignored when glint started (a job started with `&` by a non-interactive shell,
// nohup) stays ignored, as the shell's user asked.
void catch_signal(int signal) noexcept {
    struct sigaction old {};
    if (sigaction(signal, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) return;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(signal, &sa, nullptr);
}

// The launcher (tools/launcher) blocked SIGINT and SIGTERM before it executed this program, so
// that a signal of the first milliseconds waits, pending, for the handlers. With them in place
// the signals it blocked are unblocked (a pending one is delivered now), and its note is
// removed from the environment, so that programs glint starts inherit nothing of it.
void release_launcher_signals(char** env) noexcept {
    static constexpr char kNote[] = "GLINT_UNBLOCK_SIGNALS=";
    if (env == nullptr) return;
    for (char** e = env; *e != nullptr; ++e) {
        if (std::strncmp(*e, kNote, sizeof kNote - 1) != 0) continue;
        const char* which = *e + sizeof kNote - 1;
        sigset_t set{};
        sigemptyset(&set);
        if (std::strchr(which, 'I') != nullptr) sigaddset(&set, SIGINT);
        if (std::strchr(which, 'T') != nullptr) sigaddset(&set, SIGTERM);
        for (char** f = e; *f != nullptr; ++f) f[0] = f[1];  // removed in place
        sigprocmask(SIG_UNBLOCK, &set, nullptr);
        return;
    }
}

void install_early(char** env) noexcept {
    if (!g_wake_ready.load()) {
        sem_init(&g_wake, 0, 0);
        g_wake_ready.store(true);
    }
    catch_signal(SIGINT);
    catch_signal(SIGTERM);
    release_launcher_signals(env);
}

extern "C" void run_before_library_initialisers(int, char**, char** env) { install_early(env); }
// note: .preinit_array entries of the executable run before every DT_INIT of its libraries.
[[gnu::section(".preinit_array"),
  gnu::used]] constexpr void (*kPreinit)(int, char**, char**) = run_before_library_initialisers;

void write_line(const char* text, std::size_t size) noexcept {
    [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, text, size);
}

[[noreturn]] void watchdog() {
    while (sem_wait(&g_wake) != 0) {
    }
    timespec deadline{};
    clock_gettime(CLOCK_MONOTONIC, &deadline);
    deadline.tv_sec += kCancelGraceSeconds;
    while (!g_insisted.load())
        if (sem_clockwait(&g_wake, CLOCK_MONOTONIC, &deadline) != 0 && errno == ETIMEDOUT) break;
    remove_staged_now();
    static constexpr char kStuck[] =
        "glint: interrupted: the step under way did not stop within 3 s; ended it, staged "
        "outputs removed, nothing half-written left\n";
    static constexpr char kInsisted[] =
        "glint: interrupted: a second signal: ended at once, staged outputs removed, nothing "
        "half-written left\n";
    if (!g_main_reported.load()) {
        if (g_insisted.load()) write_line(kInsisted, sizeof kInsisted - 1);
        else write_line(kStuck, sizeof kStuck - 1);
    }
    _exit(kExitInterrupted);
}

}  // namespace

void install_interrupt_handlers() {
    install_early(environ);  // again: a no-op after .preinit_array, needed where it did not run
    // note: its own small stack, not the default (RLIMIT_STACK, 8 MB or more): under ulimit -v
    // a thread of the default size could not be mapped and std::thread's exception, thrown
    // before any command's guard, aborted the run (the fault suite's 600 MB case, once in CI).
    // Without a watchdog a first signal still stops the run at its next poll; only the 3 s
    // grace and the second signal's immediate end are lost.
    pthread_attr_t attr;
    if (pthread_attr_init(&attr) != 0) return;
    pthread_attr_setstacksize(&attr, 256 * 1024);
    pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
    pthread_t thread;
    (void)pthread_create(
        &thread, &attr, [](void*) -> void* { watchdog(); }, nullptr);
    pthread_attr_destroy(&attr);
}

void note_interrupt_reported() noexcept { g_main_reported.store(true); }

}  // namespace glint::cli
