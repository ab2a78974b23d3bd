// import glint: the Python face of the glint library (docs/python.md in the repository).
#include "mesh/cancel.h"
#include "mesh/front_end.h"
#include "mesh/plugin_library.h"
#include "mesh/version.h"
#include "python/bindings.h"
#include "python/interrupt.h"

#include <pybind11/pybind11.h>

#include <csignal>

namespace py = pybind11;

PYBIND11_MODULE(glint, m) {
    m.doc() = "glint: damage on 3D surfaces by light-reflection analysis (load, register, analyse)";
    m.attr("__version__") = glint::kVersion;
    // The library's messages name options as keywords (force=True), not as flags (--force).
    glint::set_front_end(glint::FrontEnd::Python);
    glint::python::register_exceptions(m);
    glint::python::bind_mesh(m);
    glint::python::bind_analysis(m);
    glint::python::bind_asymmetry(m);
    m.def(
        "cancel", [] { glint::request_cancel(SIGINT); },
        "Asks the glint calls in progress (any thread) to stop; each then raises KeyboardInterrupt.");
    // A plugin still loading on its own thread (a call interrupted in its first half second)
    // ends its dlopen before the interpreter exits: exit would run the destructors its libraries
    // registered at once, and the rest of their start-up then use what those destroyed.
    m.def("_finish_background_loads", [] {
        const py::gil_scoped_release unlocked;
        glint::detail::finish_background_loads();
    });
    py::module_::import("atexit").attr("register")(m.attr("_finish_background_loads"));
}
