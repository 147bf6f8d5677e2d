// The API 617 Level I stability screen of an FE rotor scene (level1_study) as NumPy arrays.
#include "common.hpp"
#include "binding_table.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/reports/level1_reports.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/defaults.hpp>
#include <gyrokit/study/level1_study.hpp>

#include "reports.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

// One bearing set's screen: the curve as arrays, Q0, the verdict.
py::dict screen_dict(const Level1Screen& s) {
    std::vector<double> q, logdec, bound, freq;
    std::vector<std::string> whirl;
    for (const Level1Point& p : s.curve.points) {
        q.push_back(p.q);
        logdec.push_back(p.log_decrement);
        bound.push_back(log_decrement_bound(p));
        freq.push_back(s.unit.factor * p.lambda.imag());
        whirl.push_back(to_string(p.whirl));
    }
    py::dict d;
    const auto arr = [](const std::vector<double>& v) {
        return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
    };
    d["unit"] = s.unit.name;
    d["q"] = arr(q);
    d["log_decrement"] = arr(logdec);
    d["log_decrement_bound"] = arr(bound);
    d["frequency"] = arr(freq);
    d["whirl"] = whirl;
    d["qa"] = s.qa;
    d["stage_qa"] = s.stage_qa;
    d["q0"] = s.curve.q0 ? py::object(py::float_(*s.curve.q0)) : py::object(py::none());
    d["q0_bound"] = s.curve.q0_bound;
    d["log_decrement_at_qa"] = s.at_qa.log_decrement;
    d["log_decrement_at_zero"] = s.at_zero.log_decrement;
    d["mcs"] = s.unit.factor * *s.machine.mcs;
    d["layout"] = s.layout;
    std::vector<int> nodes;
    std::vector<double> shares;
    for (const CrossCouplingStation& c : s.stations) nodes.push_back(c.node), shares.push_back(c.share);
    d["station_nodes"] = nodes;
    d["station_shares"] = shares;
    d["station_z"] = s.station_z;
    d["rigid_critical"] = s.rigid_critical ? py::object(py::float_(s.unit.factor * *s.rigid_critical))
                                           : py::object(py::none());
    d["csr"] = s.csr ? py::object(py::float_(*s.csr)) : py::object(py::none());
    d["region_boundary"] = s.region_boundary ? py::object(py::float_(*s.region_boundary)) : py::object(py::none());
    d["level2_required"] = s.level2_required;
    py::list reasons;
    for (const std::string& t : s.reasons) reasons.append(spell_fields(t, keyword_words));
    d["reasons"] = reasons;
    d["solves"] = s.curve.solves;
    d["bearing_set"] = s.bearing_set;
    py::list passed;
    for (const PassedMode& m : s.curve.passed) {
        py::dict p;
        p["frequency"] = s.unit.factor * m.lambda.imag();
        p["log_decrement"] = m.log_decrement;
        p["orbit_ratio"] = m.orbit_ratio;
        passed.append(p);
    }
    d["passed"] = passed;
    return d;
}

}  // namespace

void bind_level1(py::module_& m) {
    m.def(
        "level1",
        [](const Scene& scene, std::optional<std::string> unit, std::optional<std::string> machine,
           std::optional<double> mcs, std::optional<double> operating_speed, std::optional<double> qa,
           std::optional<double> station, std::optional<double> gas_density, std::optional<double> q_ratio,
           int intervals, const std::string& method) {
            Level1Request r;
            r.unit = unit;
            r.machine = machine;
            r.mcs = mcs;
            r.operating_speed = operating_speed;
            r.qa = qa;
            r.station = station;
            r.gas_density = gas_density;
            r.q_ratio = q_ratio;
            r.intervals = intervals;
            r.method = method;
            Level1Study st;
            {
                Released free;
                st = level1_study(scene, r);
            }
            py::dict d = screen_dict(st.verdict());
            py::list sets;
            for (const Level1Screen& s : st.screens) sets.append(screen_dict(s));
            d["bearing_sets"] = sets;
            put_diagnostics(d, st.diagnostics);
            d["tables"] = tables_list(level1_tables(st));
            d["figure"] = figure_dict(level1_figure(st, scene.title));
            return d;
        },
        py::arg("scene"), py::arg("unit") = py::none(), py::arg("machine") = py::none(), py::arg("mcs") = py::none(),
        py::arg("operating_speed") = py::none(), py::arg("qa") = py::none(), py::arg("station") = py::none(),
        py::arg("gas_density") = py::none(), py::arg("q_ratio") = py::none(), py::arg("intervals") = kLevel1Intervals,
        py::arg("method") = defaults::method);
}
