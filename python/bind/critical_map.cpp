// The undamped critical speed map of an FE rotor scene (critical_speed_map) as NumPy arrays.
#include "common.hpp"
#include "binding_table.hpp"

#include <gyrokit/analysis/critical_speed_map.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/reports/critical_map_reports.hpp>
#include <gyrokit/study/critical_map_study.hpp>

#include "reports.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

void bind_critical_map(py::module_& m) {
    m.def("critical_speed_map", [](const Scene& scene, const std::vector<double>& stiffness, int modes,
                                   const std::string& unit) {
        const SpeedUnit u = SpeedUnit::parse(unit);
        CriticalSpeedMapOptions o;
        o.stiffness = stiffness;
        o.modes = modes;
        CriticalSpeedMap map;
        {
            Released free;
            map = critical_map_study(scene, o);
        }
        const auto rows = [](const std::vector<MapPoint>& ps) {
            py::dict d;
            std::vector<double> k, w, be;
            std::vector<int> number;
            std::vector<std::string> whirl;
            for (const MapPoint& p : ps) {
                k.push_back(p.stiffness), w.push_back(p.speed), be.push_back(p.backward_error);
                number.push_back(p.number), whirl.push_back(p.whirl);
            }
            d["stiffness"] = py::array_t<double>(static_cast<py::ssize_t>(k.size()), k.data());
            d["whirl"] = whirl;
            d["critical"] = py::array_t<int>(static_cast<py::ssize_t>(number.size()), number.data());
            d["speed"] = py::array_t<double>(static_cast<py::ssize_t>(w.size()), w.data());
            d["backward_error"] = py::array_t<double>(static_cast<py::ssize_t>(be.size()), be.data());
            return d;
        };
        py::dict d;
        d["stiffness"] = map.stiffness;
        d["points"] = rows(map.points);
        d["rigid"] = rows(map.rigid);
        py::list curves;
        for (const BearingCurve& c : map.bearings) {
            py::dict cd;
            cd["name"] = c.name;
            cd["stiffness"] = c.stiffness;
            cd["speed"] = c.speed;
            curves.append(cd);
        }
        d["bearings"] = curves;
        d["max_backward_error"] = map.max_backward_error;
        d["tables"] = tables_list({critical_map_table(map, u), bearing_curve_table(map, u)});
        d["figure"] = figure_dict(critical_map_figure(map, u, scene.title));
        return d;
    }, py::arg("scene"), py::arg("stiffness"), py::arg("modes"), py::arg("unit") = "rad/s");

}
