// Frequency response functions (frequency_response) as NumPy arrays.
#include "frf.hpp"

#include <gyrokit/analysis/frequency_response.hpp>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;

void bind_frf(py::module_& m) {
    m.def("frf", [](const GyroscopicSystem& s, double spin, const std::vector<double>& frequencies, int input,
                    const std::vector<int>& outputs, const std::string& solver) {
        const SolverKind kind = parse_solver_kind(solver);
        FrequencyResponse r;
        {
            py::gil_scoped_release free;
            r = frequency_response(s, spin, frequencies, input, outputs, kind);
        }
        return r.H;
    }, py::arg("system"), py::arg("spin"), py::arg("frequencies"), py::arg("input"), py::arg("outputs"),
          py::arg("solver"));
}
