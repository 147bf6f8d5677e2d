// The static analysis of an FE rotor scene (static_study) as NumPy arrays.
#include "binding_table.hpp"

#include <gyrokit/reports/static_reports.hpp>
#include <gyrokit/study/static_study.hpp>

#include "reports.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

template <class T, class F>
py::array_t<double> column(const std::vector<T>& rows, const F& value) {
    py::array_t<double> a(static_cast<py::ssize_t>(rows.size()));
    auto v = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < rows.size(); ++i) v(static_cast<py::ssize_t>(i)) = value(rows[i]);
    return a;
}

}  // namespace

void bind_statics(py::module_& m) {
    m.def("static", [](const Scene& scene, double gravity, const std::vector<std::vector<double>>& loads) {
        StaticOptions o;
        o.gravity = gravity;
        for (const auto& l : loads) {
            if (l.size() != 5) throw InputError("loads: each entry is (node, fx, fy, mx, my)");
            o.loads.push_back({static_cast<int>(l[0]), l[1], l[2], l[3], l[4]});
        }
        const StaticResult s = static_study(scene, o);
        py::dict d;
        py::dict nodes, sections, reactions;
        nodes["node"] = column(s.nodes, [](const StaticNode& n) { return n.node; });
        nodes["z"] = column(s.nodes, [](const StaticNode& n) { return n.z; });
        nodes["x"] = column(s.nodes, [](const StaticNode& n) { return n.x; });
        nodes["y"] = column(s.nodes, [](const StaticNode& n) { return n.y; });
        nodes["slope_x"] = column(s.nodes, [](const StaticNode& n) { return n.slope_x; });
        nodes["slope_y"] = column(s.nodes, [](const StaticNode& n) { return n.slope_y; });
        sections["element"] = column(s.sections, [](const StaticSection& c) { return c.element; });
        sections["z"] = column(s.sections, [](const StaticSection& c) { return c.z; });
        sections["shear_x"] = column(s.sections, [](const StaticSection& c) { return c.shear_x; });
        sections["moment_x"] = column(s.sections, [](const StaticSection& c) { return c.moment_x; });
        sections["shear_y"] = column(s.sections, [](const StaticSection& c) { return c.shear_y; });
        sections["moment_y"] = column(s.sections, [](const StaticSection& c) { return c.moment_y; });
        std::vector<std::string> names;
        for (const auto& r : s.reactions) names.push_back(r.what);
        reactions["reaction"] = names;
        reactions["node"] = column(s.reactions, [](const StaticReaction& r) { return r.node; });
        reactions["z"] = column(s.reactions, [](const StaticReaction& r) { return r.z; });
        reactions["fx"] = column(s.reactions, [](const StaticReaction& r) { return r.fx; });
        reactions["fy"] = column(s.reactions, [](const StaticReaction& r) { return r.fy; });
        reactions["mx"] = column(s.reactions, [](const StaticReaction& r) { return r.mx; });
        reactions["my"] = column(s.reactions, [](const StaticReaction& r) { return r.my; });
        d["nodes"] = nodes;
        d["sections"] = sections;
        d["reactions"] = reactions;
        d["weight"] = s.weight;
        d["backward_error"] = s.backward_error;
        d["balance_error"] = s.balance_error;
        d["condition"] = s.condition;
        d["error_bound"] = s.error_bound;
        d["tables"] = tables_list(static_tables(s, scene.length_unit()));
        d["figure"] = figure_dict(static_figure(s, scene.title, scene.length_unit()));
        return d;
    }, py::arg("scene"), py::arg("gravity"), py::arg("loads"));
}
