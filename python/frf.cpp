// Frequency response functions (frequency_response) as NumPy arrays, with the CLI's table
// and Bode and polar figures in the call's unit.
#include "common.hpp"
#include "frf.hpp"

#include "reports.hpp"

#include <gyrokit/analysis/frequency_response.hpp>
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/reports/frf_reports.hpp>
#include <gyrokit/reports/response_reports.hpp>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <fmt/format.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace gyrokit_python {

std::vector<Probe> probes_of(const GyroscopicSystem& s, const std::vector<std::pair<int, double>>& list) {
    std::vector<Probe> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const auto [node, angle] = list[i];
        if (!(std::abs(angle) <= 360.0))
            throw InputError(fmt::format("probes[{}]: angle = {}: out of range; allowed: -360 to 360 (degrees from +x "
                                         "towards +y)",
                                         i, angle));
        const std::string name = fmt::format("{}@{:g}", node, angle);
        for (const Probe& p : out)
            if (p.name == name) throw InputError(fmt::format("probes[{}]: {} is listed twice; allowed: each once", i, name));
        try {
            out.push_back(probe_at_node(s, name, node, angle));
        } catch (const InputError& e) {
            throw InputError(fmt::format("probes[{}]: {}", i, e.what()));
        }
    }
    return out;
}

}  // namespace gyrokit_python

void bind_frf(py::module_& m) {
    m.def("frf", [](const GyroscopicSystem& s, double spin, const std::vector<double>& frequencies, int input,
                    std::vector<int> outputs, const std::string& solver, const std::string& unit,
                    const std::vector<std::pair<int, double>>& probe_list, const std::string& length_unit) {
        const SolverKind kind = parse_solver_kind(solver);
        const SpeedUnit u = SpeedUnit::parse(unit);
        const std::vector<Probe> probes = probes_of(s, probe_list);
        if (!probes.empty()) outputs = probe_dofs(probes);
        FrequencyResponse r;
        {
            Released free;   // Ctrl-C stops it at the next frequency
            r = frequency_response(s, spin, frequencies, input, outputs, kind);
        }
        // Probes: their readings are the outputs, named "NODE@ANGLE".
        ProbeOutputs named{s.dof_names, s.dof_units, {}};
        if (!probes.empty()) {
            named = probe_outputs(s, probes);
            r.H = probe_readings(probes, r.outputs, r.H);
            r.outputs = named.outputs;
        }
        py::dict d;
        d["H"] = r.H;   // SI: m/N, rad/N, ...; the tables and figures in the scene's length unit
        to_length_unit(r.outputs, r.H, named.units, LengthUnit::parse(length_unit));
        d["names"] = std::vector<std::string>(named.names.begin() + s.size(), named.names.end());
        d["tables"] = tables_list({frf_table(named.names, named.units, r, u)});
        d["figure"] = figure_dict(frf_figure(named.names, named.units, r, u, false));
        d["polar_figure"] = figure_dict(frf_figure(named.names, named.units, r, u, true));
        return d;
    }, py::arg("system"), py::arg("spin"), py::arg("frequencies"), py::arg("input"), py::arg("outputs"),
          py::arg("solver"), py::arg("unit") = "rad/s", py::arg("probes") = std::vector<std::pair<int, double>>{},
          py::arg("length_unit") = "m");
}
