// Cooperative cancellation for long library loops (loading, fitting, sweeping).
//
// The library never installs signal handlers (only tools/ does); it polls a process-wide
// flag at points where stopping is safe and throws Cancelled from there, so the stack
// unwinds through RAII owners (staged output folders, device objects) and nothing is left
// half-written. request_cancel() only stores into a lock-free atomic: it may be called from
// a signal handler.
#pragma once

#include "mesh/error.h"

#include <filesystem>

namespace glint {

/// Thrown by throw_if_cancelled() once cancellation was requested (glint exits 130).
class Cancelled : public Error {
  public:
    using Error::Error;
};

/// Asks every loop that polls to stop; `signal` (e.g. SIGINT) is kept for the message.
/// Async-signal-safe.
void request_cancel(int signal) noexcept;
/// True once request_cancel() was called (and not reset).
[[nodiscard]] bool cancel_requested() noexcept;
/// The signal passed to request_cancel(), 0 when none.
[[nodiscard]] int cancel_signal() noexcept;
/// Clears the request (tests, and hosts such as the Python module that run many jobs).
void reset_cancel() noexcept;
/// \throw Cancelled naming the signal when cancellation was requested.
void throw_if_cancelled();

// Staged outputs (temporary files, staging folders) of this process. The cooperative stop
// removes them as the stack unwinds; when a step does not come back (a library call that
// cannot poll), the command line's watchdog removes what is still listed here before it ends
// the process, so even then nothing half-written is left under a name of the user's.

/// Lists a staged path (a file or a folder) until untrack_staged(). Thread-safe.
void track_staged(const std::filesystem::path& path);
/// Takes a path off the list (committed, or removed by its owner). Thread-safe.
void untrack_staged(const std::filesystem::path& path) noexcept;
/// Removes every listed path (folders with their contents) and empties the list; returns how
/// many it removed. For the watchdog thread: never throws.
std::size_t remove_staged_now() noexcept;

}  // namespace glint
