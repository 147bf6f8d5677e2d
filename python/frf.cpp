// Frequency response functions (frequency_response) as NumPy arrays, with the CLI's table
// and Bode and polar figures in the call's unit.
#include "frf.hpp"

#include "reports.hpp"

#include <gyrokit/analysis/frequency_response.hpp>
#include <gyrokit/reports/frf_reports.hpp>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

void bind_frf(py::module_& m) {
    m.def("frf", [](const GyroscopicSystem& s, double spin, const std::vector<double>& frequencies, int input,
                    const std::vector<int>& outputs, const std::string& solver, const std::string& unit) {
        const SolverKind kind = parse_solver_kind(solver);
        const SpeedUnit u = SpeedUnit::parse(unit);
        FrequencyResponse r;
        {
            py::gil_scoped_release free;
            r = frequency_response(s, spin, frequencies, input, outputs, kind);
        }
        py::dict d;
        d["H"] = r.H;
        d["tables"] = tables_list({frf_table(s.dof_names, s.dof_units, r, u)});
        d["figure"] = figure_dict(frf_figure(s.dof_names, s.dof_units, r, u, false));
        d["polar_figure"] = figure_dict(frf_figure(s.dof_names, s.dof_units, r, u, true));
        return d;
    }, py::arg("system"), py::arg("spin"), py::arg("frequencies"), py::arg("input"), py::arg("outputs"),
          py::arg("solver"), py::arg("unit") = "rad/s");
}
