// Long glint calls from Python: the GIL released, Ctrl-C honoured, glint's errors as Python
// exceptions.
//
// glint cancels cooperatively (mesh/cancel.h): library loops poll a process-wide flag and
// throw Cancelled. Python runs its signal handlers only in the main thread, and only between
// bytecodes, so a call that blocked the main thread in C++ would never see Ctrl-C. Hence
// run_interruptible(): the work runs on a worker thread while the calling thread, with the GIL
// released, wakes every kPollInterval, takes the GIL briefly and runs PyErr_CheckSignals().
// When a handler raised (KeyboardInterrupt from Ctrl-C, or whatever a custom handler raises),
// it asks glint to cancel, waits until the worker has unwound (staged outputs removed) and
// re-raises the handler's exception.
//
// note: the cancellation flag is process-wide: Ctrl-C stops every glint call in progress, and
// each call clears the flag when it starts. A call is the whole public function (CallScope):
// a request that arrives while it loads its inputs (glint.cancel() from another thread) stops
// its analysis, not only the load (issue 52: it was cleared when the analysis began).
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint::python {

/// How often a waiting call looks for Python signals: Ctrl-C is seen within this.
inline constexpr std::chrono::milliseconds kPollInterval{50};

/// The span of one public call (glint.analyse, glint.load, …): the cancellation flag is cleared
/// when the outermost scope begins and ends, not by each run_interruptible() inside it.
class CallScope {
  public:
    CallScope();
    ~CallScope();
    CallScope(const CallScope&) = delete;
    CallScope& operator=(const CallScope&) = delete;
};

/// Runs `work` on a worker thread (see file comment). Call with the GIL held; `work` must not
/// touch Python objects. Rethrows what `work` threw (translated by the module's exception
/// translator); throws pybind11::error_already_set with the signal handler's exception.
void run_interruptible(const std::function<void()>& work);

/// The same for work with a result.
template <class Work>
auto run_interruptible_value(Work&& work) -> decltype(work()) {
    std::optional<decltype(work())> result;
    run_interruptible([&] { result.emplace(work()); });
    return std::move(*result);
}

/// glint's exception types (module.cpp registers them): glint.Error and its subclasses, and
/// glint.GlintWarning (a UserWarning).
void register_exceptions(pybind11::module_& m);

/// Issues each message once as warnings.warn(message, glint.GlintWarning), attributed to the
/// Python caller. \throw pybind11::error_already_set when a warnings filter raises.
void warn(const std::vector<std::string>& messages);

}  // namespace glint::python
