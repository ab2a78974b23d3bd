#include "python/interrupt.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "python/keywords.h"

#include <atomic>
#include <condition_variable>
#include <csignal>
#include <cstring>
#include <exception>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace py = pybind11;

namespace glint::python {

namespace {

// The exception classes, created once when the module is imported (never freed: they live
// as long as the interpreter).
PyObject* g_error = nullptr;
PyObject* g_input_error = nullptr;
PyObject* g_io_error = nullptr;
PyObject* g_device_error = nullptr;
PyObject* g_warning = nullptr;

PyObject* new_exception(py::module_& m, const char* name, py::tuple bases, const char* doc) {
    const std::string qualified = std::string("glint.") + name;
    PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
    if (type == nullptr) throw py::error_already_set();
    m.add_object(name, py::handle(type));  // the module holds one reference, g_* another
    Py_INCREF(type);
    return type;
}

}  // namespace

namespace {

// A message as Python text. Messages quote input bytes, which need not be UTF-8 (a damaged
// file): PyErr_SetString would fail to decode them and raise the exception with an empty
// message, so undecodable bytes are written as \xNN instead.
py::str message_text(const char* what) {
    PyObject* text =
        PyUnicode_DecodeUTF8(what, static_cast<Py_ssize_t>(std::strlen(what)), "backslashreplace");
    if (text == nullptr) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(text);
}

void set_error(PyObject* type, const char* what) {
    PyErr_SetObject(type, message_text(what).ptr());
}

}  // namespace

void register_exceptions(py::module_& m) {
    const py::handle exception(PyExc_Exception);
    g_error = new_exception(
        m, "Error", py::make_tuple(exception),
        "Base of glint's errors; the message is glint's one line (what, where, found, expected).");
    const py::handle error(g_error);
    g_input_error =
        new_exception(m, "InputError", py::make_tuple(error, py::handle(PyExc_ValueError)),
                      "Bad input: a malformed file, an invalid option (glint exit code 2).");
    g_io_error = new_exception(m, "IoError", py::make_tuple(error, py::handle(PyExc_OSError)),
                               "A read or write failed (glint exit code 3).");
    g_device_error =
        new_exception(m, "DeviceError", py::make_tuple(error, py::handle(PyExc_RuntimeError)),
                      "No usable render device, or a device call failed (glint exit code 3).");
    g_warning = new_exception(m, "GlintWarning", py::make_tuple(py::handle(PyExc_UserWarning)),
                              "What a glint call warns of (an assumed unit, a fit taken as "
                              "given, a repaired input): issued with warnings.warn.");
    // note: Cancelled derives from glint::Error, so it is caught first; it becomes Python's
    // own KeyboardInterrupt, as a Ctrl-C anywhere else in Python does.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Cancelled& e) {
            set_error(PyExc_KeyboardInterrupt, e.what());
        } catch (const OptionError& e) {
            // The library names an option by its scenario key (sweep.size); Python by its
            // keyword (size).
            const std::string keyword = keyword_of_option(e.key());
            set_error(g_input_error, keyword.empty() ? e.what() : e.named(keyword).c_str());
        } catch (const InputError& e) {
            set_error(g_input_error, e.what());
        } catch (const IoError& e) {
            set_error(g_io_error, e.what());
        } catch (const DeviceError& e) {
            set_error(g_device_error, e.what());
        } catch (const Error& e) {
            set_error(g_error, e.what());
        }
    });
}

void warn(const std::vector<std::string>& messages) {
    std::set<std::string> issued;  // one call's warnings may repeat (an input's, the run's)
    for (const std::string& message : messages)
        if (issued.insert(message).second &&
            PyErr_WarnEx(g_warning, py::cast<std::string>(message_text(message.c_str())).c_str(),
                         1) != 0)
            throw py::error_already_set();  // a filter turned the warning into an error
}

namespace {
std::atomic<int> g_call_depth{0};
}  // namespace

CallScope::CallScope() {
    if (g_call_depth.fetch_add(1) == 0) reset_cancel();
}

CallScope::~CallScope() {
    if (g_call_depth.fetch_sub(1) == 1) reset_cancel();
}

void run_interruptible(const std::function<void()>& work) {
    const CallScope scope;  // a call of its own unless a public function's scope holds it
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    std::exception_ptr failure;
    std::thread worker([&] {
        try {
            work();
        } catch (...) {
            failure = std::current_exception();
        }
        const std::lock_guard lock(mutex);
        done = true;
        finished.notify_one();
    });
    bool signalled = false;  // a Python signal handler raised; its exception is pending
    {
        const py::gil_scoped_release release;
        std::unique_lock lock(mutex);
        while (!finished.wait_for(lock, kPollInterval, [&] { return done; })) {
            if (signalled) continue;  // cancelling: wait for the worker to unwind
            lock.unlock();
            {
                const py::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) {
                    signalled = true;
                    request_cancel(SIGINT);
                }
            }
            lock.lock();
        }
    }
    worker.join();
    if (signalled)
        throw py::error_already_set();  // the handler's exception, set by PyErr_CheckSignals
    if (failure) std::rethrow_exception(failure);
}

}  // namespace glint::python
