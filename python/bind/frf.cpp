// Frequency response functions (frequency_response) as NumPy arrays, with the CLI's table
// and Bode and polar figures in the call's unit.
#include "binding_table.hpp"
#include "common.hpp"
#include "frf.hpp"
#include "request.hpp"

#include "reports.hpp"

#include <gyrokit/study/frf_study.hpp>
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
    // The study of the library (frf_study): the request's keywords, the input and outputs by name.
    m.def("frf", [](const py::object& model, const py::dict& request, const std::string& input, double speed,
                    std::optional<std::vector<double>> frequencies, const std::vector<std::string>& dofs,
                    const std::vector<std::pair<int, double>>& probe_list) {
        const ModelArg a(model);
        FrfRequest rq;
        rq.input = input;
        rq.speed = speed;
        rq.frequencies = std::move(frequencies);
        rq.dofs = dofs;
        rq.probes = probes_of(a.system(), probe_list);
        const RotorRequest common = rotor_request(request);
        FrfStudy st;
        {
            Released free;   // Ctrl-C stops it at the next frequency
            st = frf_study(a.scene(), common, rq);
        }
        const FrequencyResponse& r = st.response;
        const SpeedUnit& u = st.unit;
        py::dict d;
        d["unit"] = u.name;
        d["input"] = input;
        d["speed"] = r.spin;
        d["frequencies"] = r.frequencies;
        d["H"] = st.si;   // SI: m/N, rad/N, ...; the tables and figures in the scene's length unit
        d["names"] = std::vector<std::string>(st.named.names.begin() + a.system().size(), st.named.names.end());
        if (rq.probes.empty()) {
            std::vector<std::string> names;
            for (const int k : r.outputs) names.push_back(st.named.names[static_cast<std::size_t>(k)]);
            d["names"] = names;
        }
        put_diagnostics(d, st.diagnostics);
        d["tables"] = tables_list({frf_table(st.named.names, st.named.units, r, u)});
        d["figure"] = figure_dict(frf_figure(st.named.names, st.named.units, r, u, false));
        d["polar_figure"] = figure_dict(frf_figure(st.named.names, st.named.units, r, u, true));
        return d;
    }, py::arg("model"), py::arg("request"), py::arg("input"), py::arg("speed"), py::arg("frequencies"),
          py::arg("dofs"), py::arg("probes"));
}
