// The compiled core of the Python package `gyrokit` (gyrokit/_core): the
// library's system, scene and analyses with NumPy/SciPy arrays in and out.
// The Python layer (gyrokit/__init__.py) adds keyword defaults from scenes,
// result classes with to_pandas() and plot().
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/gyrokit.hpp>

#include "binding_table.hpp"
#include "common.hpp"
#include "frf.hpp"
#include "models.hpp"
#include "reports.hpp"
#include "system.hpp"

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace py = pybind11;
using namespace gyrokit;

namespace gyrokit_python {

// Python's keyword arguments for the library's option fields (as the CLI's flag_words).
std::string keyword_words(const std::string& field) {
    if (field == "lanczos_vectors") return "lanczos =";
    // Names that read as nouns in a message ("dofs and probes: allowed: one of them").
    for (const char* noun : {"speeds", "dofs", "probes", "input", "frequencies", "fill"})
        if (field == noun) return noun;
    if (field == "units") return "unit =";
    if (field == "rows") return "result.table('campbell')";
    if (field == "plot") return "result.plot(FILE.svg)";
    if (field == "rigid_body") return "result.rigid_body";
    return "";   // the others are named as in the library: "modes =
}

// The library's parallelism rule; its note (jobs capped to the cores) as a Python warning.
Workers threads(int jobs) {
    std::vector<std::string> notes;
    const int count = worker_count(jobs, &notes);
    for (const auto& n : notes)
        py::module_::import("warnings").attr("warn")(spell_fields(n, keyword_words), py::module_::import("builtins").attr("RuntimeWarning"));
    return Workers{count, WorkerKind::Threads};
}

bool on_main_thread() {
    const py::object threading = py::module_::import("threading");
    return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace gyrokit_python

PYBIND11_MODULE(_core, m) {
    m.doc() = "gyrokit's compiled core; use the package gyrokit";
    static py::exception<Error> error(m, "Error");
    static py::exception<InputError> input_error(m, "InputError", error.ptr());
    static py::exception<SolverError> solver_error(m, "SolverError", error.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Interrupted&) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        } catch (const InputError& e) {
            PyErr_SetString(input_error.ptr(), e.message(gyrokit_python::keyword_words).c_str());
        } catch (const SolverError& e) {
            PyErr_SetString(solver_error.ptr(), e.message(gyrokit_python::keyword_words).c_str());
        } catch (const Error& e) {
            PyErr_SetString(error.ptr(), e.message(gyrokit_python::keyword_words).c_str());
        }
    });

    py::class_<Scene> scene = bind_system(m);
    bind_models(m, scene);
#define GYROKIT_ADD_BINDING(name) bind_##name(m);
    GYROKIT_BINDINGS(GYROKIT_ADD_BINDING)
#undef GYROKIT_ADD_BINDING

    // The table of defaults (study/defaults.hpp): the package's signatures take their values from it.
    m.def("defaults", [] {
        py::list rows;
        for (const defaults::Entry& e : defaults::table())
            rows.append(py::dict(py::arg("name") = e.name, py::arg("value") = e.value, py::arg("meaning") = e.meaning,
                                 py::arg("option") = e.option, py::arg("keyword") = e.keyword,
                                 py::arg("command") = e.command, py::arg("function") = e.function));
        return rows;
    });
    m.attr("__version__") = GYROKIT_VERSION;
}
