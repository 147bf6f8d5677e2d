// The mesh convergence of an FE rotor scene (mesh_convergence_study) as lists.
#include "common.hpp"
#include "binding_table.hpp"

#include <gyrokit/reports/mesh_convergence_reports.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/defaults.hpp>
#include <gyrokit/study/mesh_convergence_study.hpp>

#include "reports.hpp"

#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

void bind_mesh(py::module_& m) {
    m.def(
        "mesh_convergence",
        [](const Scene& scene, std::optional<std::string> unit, double tolerance, int levels) {
            MeshConvergenceRequest r;
            r.unit = unit;
            r.tolerance = tolerance;
            r.levels = levels;
            MeshConvergenceStudy s;
            {
                Released free;
                s = mesh_convergence_study(scene, r);
            }
            const double f = s.unit.factor;
            py::dict d;
            d["unit"] = s.unit.name;
            d["tolerance"] = s.tolerance;
            d["top_speed"] = f * s.top_speed;
            std::vector<int> factors, elements, dofs;
            for (const MeshLevel& l : s.levels) {
                factors.push_back(l.factor);
                elements.push_back(l.elements);
                dofs.push_back(l.dofs);
            }
            d["factors"] = factors;
            d["elements"] = elements;
            d["dofs"] = dofs;
            py::list quantities;
            for (const MeshQuantity& q : s.quantities) {
                py::dict x;
                x["name"] = q.name;
                std::vector<double> v;
                for (const double y : q.values) v.push_back(f * y);
                x["values"] = v;
                x["change"] = q.change;
                x["converged"] = q.converged;
                quantities.append(x);
            }
            d["quantities"] = quantities;
            d["chosen"] = s.chosen;
            d["section_elements"] = s.section_elements;
            put_diagnostics(d, s.diagnostics);
            d["tables"] = tables_list(mesh_tables(s));
            return d;
        },
        py::arg("scene"), py::arg("unit") = py::none(), py::arg("tolerance") = defaults::mesh_tolerance,
        py::arg("levels") = defaults::mesh_levels);
}
