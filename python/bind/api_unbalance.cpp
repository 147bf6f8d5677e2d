// The API 617 unbalance cases of an FE rotor scene (api_unbalance_study) as NumPy arrays.
#include "common.hpp"
#include "binding_table.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/reports/api_unbalance_reports.hpp>
#include <gyrokit/reports/critical_reports.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/api_unbalance_study.hpp>
#include <gyrokit/study/defaults.hpp>

#include "reports.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

py::dict case_dict(const ApiUnbalanceStudy& s, const ApiUnbalanceCase& c) {
    const double f = s.unit.factor;
    py::dict d;
    d["layout"] = std::string(to_string(c.placement.layout));
    py::list loads;
    for (const ApiUnbalanceLoad& l : c.loads) {
        py::dict x;
        x["node"] = l.node;
        x["z"] = l.z;
        x["weight"] = l.weight;
        x["weight_of"] = l.weight_of;
        x["unbalance"] = l.unbalance;
        x["phase"] = l.phase;
        loads.append(x);
    }
    d["loads"] = loads;
    py::list criticals;
    for (const ApiCritical& k : c.criticals) {
        py::dict x;
        x["speed"] = f * k.critical.speed;
        x["whirl"] = to_string(k.critical.mode.whirl);
        x["amplification"] = k.critical.amplification;
        x["af_method"] = to_string(k.critical.amplification_method);
        x["af_dof"] = k.critical.amplification_dof;
        x["af_note"] = spell_fields(k.critical.amplification_note, keyword_words);
        x["side"] = std::string(to_string(k.margin.side));
        x["margin"] = k.margin.percent;
        x["required"] = k.required;
        x["met"] = k.met;
        criticals.append(x);
    }
    d["criticals"] = criticals;
    std::vector<double> pp, at, checked, limit, ratio;
    for (const ApiAmplitude& a : c.amplitudes) {
        pp.push_back(a.peak_to_peak);
        at.push_back(f * a.speed);
        checked.push_back(a.scaled);
        limit.push_back(a.limit);
        ratio.push_back(a.ratio);
    }
    d["peak_to_peak"] = pp;
    d["at"] = at;
    d["checked"] = checked;
    d["limit"] = limit;
    d["ratio"] = ratio;
    d["curves"] = c.curves;
    d["a1"] = c.a1;
    d["avl"] = c.avl;
    d["scc"] = c.scale;
    d["concern"] = f * c.concern;
    d["margins_met"] = c.margins_met;
    d["verdict"] = std::string(to_string(c.verdict));
    py::list reasons;
    for (const std::string& t : c.reasons) reasons.append(spell_fields(t, keyword_words));
    d["reasons"] = reasons;
    return d;
}

}  // namespace

void bind_api_unbalance(py::module_& m) {
    m.def(
        "api_unbalance",
        [](const Scene& scene, std::optional<std::string> unit, std::optional<double> mcs,
           std::optional<double> min_speed, std::optional<double> trip_speed, int speeds) {
            ApiUnbalanceRequest r;
            r.unit = unit;
            r.mcs = mcs;
            r.min_speed = min_speed;
            r.trip_speed = trip_speed;
            r.speeds = speeds;
            ApiUnbalanceStudy s;
            {
                Released free;
                s = api_unbalance_study(scene, r);
            }
            const double f = s.unit.factor;
            py::dict d;
            d["unit"] = s.unit.name;
            d["verdict"] = std::string(to_string(s.verdict));
            py::list reasons;
            for (const std::string& t : s.reasons) reasons.append(spell_fields(t, keyword_words));
            d["reasons"] = reasons;
            d["mcs"] = f * s.mcs;
            d["min_speed"] = f * s.min_speed;
            d["trip_speed"] = f * s.trip_speed;
            d["search_to"] = f * s.search_to;
            std::vector<std::string> names;
            std::vector<bool> probe;
            std::vector<int> nodes;
            std::vector<double> z, clearance;
            for (const ApiLocation& l : s.locations) {
                names.push_back(l.name);
                probe.push_back(l.probe);
                nodes.push_back(l.node);
                z.push_back(l.z);
                clearance.push_back(l.clearance);
            }
            d["locations"] = names;
            d["probe"] = probe;
            d["nodes"] = nodes;
            d["z"] = z;
            d["clearance"] = clearance;
            std::vector<double> w;
            for (const double x : s.response_speeds) w.push_back(f * x);
            d["speeds"] = w;
            py::list cases;
            for (const ApiUnbalanceCase& c : s.cases) cases.append(case_dict(s, c));
            d["cases"] = cases;
            d["solves"] = s.solves;
            put_diagnostics(d, s.diagnostics);
            d["tables"] = tables_list(api_unbalance_tables(s));
            d["figure"] = figure_dict(api_unbalance_figure(s, scene.title));
            return d;
        },
        py::arg("scene"), py::arg("unit") = py::none(), py::arg("mcs") = py::none(), py::arg("min_speed") = py::none(),
        py::arg("trip_speed") = py::none(), py::arg("speeds") = defaults::api_speeds);
}
