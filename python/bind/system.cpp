// The System (from NumPy or SciPy matrices) and the Scene, and scene files read
// (load_scene) or parsed from text (parse_scene).
#include "system.hpp"

#include "reports.hpp"

#include <gyrokit/reports/model_reports.hpp>

#include <gyrokit/gyrokit.hpp>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <map>
#include <string>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

// A matrix argument: a SciPy sparse matrix (taken as CSC, one copy into Eigen)
// or anything NumPy turns into a 2-D float array.
SparseMatrix to_matrix(const py::object& A, const std::string& name) {
    const py::module_ np = py::module_::import("numpy");
    // A complex matrix would lose its imaginary part to a cast with only a warning.
    const auto refuse_complex = [&](const py::object& values) {
        if (!np.attr("iscomplexobj")(values).cast<bool>()) return;
        if (np.attr("any")(np.attr("imag")(values)).cast<bool>())
            throw InputError(name + ": has complex entries; allowed: a real matrix (M, D, G, K, N, K2 are real; a "
                                    "complex unbalance goes to `unbalance`)");
    };
    if (py::hasattr(A, "tocsc")) {
        // A copy, checked in full (indices in range, indptr monotone) and sorted: the
        // arrays are then read as they are, and a wrong index would read out of bounds.
        py::object csc = A.attr("tocsc")(py::arg("copy") = true);
        try {
            csc.attr("check_format")(py::arg("full_check") = true);
        } catch (const py::error_already_set& e) {
            throw InputError(name + ": not a valid sparse matrix (" + std::string(py::str(e.value())) +
                             "); allowed: a SciPy sparse matrix with indices in range");
        }
        refuse_complex(csc.attr("data"));
        csc.attr("sort_indices")();
        csc.attr("sum_duplicates")();
        return csc.attr("astype")(np.attr("float64")).cast<SparseMatrix>();
    }
    py::object source = A;
    if (np.attr("iscomplexobj")(A).cast<bool>()) {
        refuse_complex(np.attr("asarray")(A));
        source = np.attr("real")(np.attr("asarray")(A));   // zero imaginary parts: the real matrix, no warning
    }
    py::array_t<double, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(source);
    } catch (const py::error_already_set&) {
    }
    if (!a || a.ndim() != 2)
        throw InputError(name + ": expected a 2-D array or a SciPy sparse matrix");
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> m(a.data(), a.shape(0),
                                                                                              a.shape(1));
    return to_sparse(Eigen::MatrixXd(m));
}

GyroscopicSystem make_from_arrays(const py::object& M, const py::object& K, const py::object& D, const py::object& G,
                                  const py::object& N, const py::object& K2, const py::dict& damping,
                                  const py::object& unbalance, const py::object& dof_names,
                                  const py::object& whirl_pairs) {
    GyroscopicSystem s;
    s.M = to_matrix(M, "M");
    s.K = to_matrix(K, "K");
    if (!D.is_none()) s.damping.push_back({"D", to_matrix(D, "D")});
    for (const auto& [name, value] : damping) {
        const std::string n = py::str(name);
        s.damping.push_back({n, to_matrix(py::reinterpret_borrow<py::object>(value), "damping['" + n + "']")});
    }
    if (!G.is_none()) s.G = to_matrix(G, "G");
    if (!N.is_none()) s.N = to_matrix(N, "N");
    if (!K2.is_none()) s.K2 = to_matrix(K2, "K2");
    if (!unbalance.is_none()) s.unbalance = unbalance.cast<Eigen::VectorXcd>();
    const int n = s.size();
    if (!dof_names.is_none()) {
        s.dofs.names = dof_names.cast<std::vector<std::string>>();
    } else {
        for (int i = 0; i < n; ++i) s.dofs.names.push_back("q" + std::to_string(i));
    }
    if (!whirl_pairs.is_none()) {
        try {
            s.whirl_pairs = whirl_pairs.cast<std::vector<std::pair<int, int>>>();
        } catch (const py::cast_error&) {
            throw InputError(fmt::format("whirl_pairs = {}: allowed: pairs of whole-number DOF indices (x, y), e.g. "
                                         "[[0, 1], [2, 3]]",
                                         std::string(py::repr(whirl_pairs)).substr(0, 80)));
        }
    } else if (n % 2 == 0) {
        for (int i = 0; i < n; i += 2) s.whirl_pairs.emplace_back(i, i + 1);   // (x, y) pairs, as a scene's default
    }
    s.validate("System");
    return s;
}

}  // namespace

py::class_<Scene> bind_system(py::module_& m) {
    py::class_<GyroscopicSystem>(m, "System", "A gyroscopic system M z'' + (D + w G) z' + (K + w N + w^2 K2) z = w^2 u")
        .def(py::init(&make_from_arrays), py::arg("M"), py::arg("K"), py::arg("D") = py::none(),
             py::arg("G") = py::none(), py::arg("N") = py::none(), py::arg("K2") = py::none(),
             py::arg("damping") = py::dict(), py::arg("unbalance") = py::none(), py::arg("dof_names") = py::none(),
             py::arg("whirl_pairs") = py::none())
        .def_property_readonly("size", &GyroscopicSystem::size)
        .def_property_readonly("dof_names", [](const GyroscopicSystem& s) { return s.dofs.names; })
        .def_property_readonly("whirl_pairs", [](const GyroscopicSystem& s) { return s.whirl_pairs; })
        .def_property_readonly("damping_names", &GyroscopicSystem::damping_names)
        .def_property_readonly("M", [](const GyroscopicSystem& s) { return SparseMatrix(s.M); })
        .def_property_readonly("K", [](const GyroscopicSystem& s) { return SparseMatrix(s.K); })
        .def_property_readonly("G", [](const GyroscopicSystem& s) { return SparseMatrix(s.G); })
        .def_property_readonly("unbalance", [](const GyroscopicSystem& s) { return s.unbalance; })
        .def("damping_matrix", &GyroscopicSystem::damping_matrix, py::arg("speed") = 0.0)
        .def("__repr__", [](const GyroscopicSystem& s) {
            return "<gyrokit.System: " + std::to_string(s.size()) + " DOFs, " + std::to_string(s.damping.size()) +
                   " damping components, " + std::to_string(s.bearings.size()) + " bearing tables>";
        });

    py::class_<Scene> scene(m, "Scene", "A scene file: a model with its analysis settings");
    scene.def_readonly("path", &Scene::path)
        .def_readonly("title", &Scene::title)
        .def_readonly("inputs", &Scene::inputs, "the files read to build it: what no result of it may be saved over")
        .def_property_readonly("length_unit", [](const Scene& s) { return s.length_unit().name; })
        .def_property_readonly("model_type", &Scene::model_type)
        .def_readonly("system", &Scene::system)
        .def_property_readonly("modes", [](const Scene& s) { return s.solver.modes; })
        .def_property_readonly("harmonics", [](const Scene& s) { return s.analysis.harmonics; })
        .def_property_readonly("target_order", [](const Scene& s) { return s.solver.target_order; })
        .def_property_readonly("target", [](const Scene& s) { return s.solver.target; })
        .def_property_readonly("f_cut", [](const Scene& s) { return s.analysis.f_cut; })
        .def_property_readonly("solver", [](const Scene& s) { return to_string(s.solver.kind); })
        .def_property_readonly("speeds", [](const Scene& s) -> py::object {
            if (!s.speeds) return py::none();
            const std::vector<double> p = s.speed_points();
            return py::array_t<double>(static_cast<py::ssize_t>(p.size()), p.data());
        }, "the [speeds] grid in rad/s (None without [speeds])")
        .def_property_readonly("speed_unit", [](const Scene& s) { return s.speed_unit.name; },
                               "[speeds] units: the unit results are given in unless a call names one");

    // What a model is: the CLI's `gyrokit model` table and, for an FE rotor, its drawing.
    m.def("model_summary", [](const Scene& scene) {
        py::dict d;
        d["tables"] = tables_list({model_summary(scene)});
        d["figure"] = scene.fe_rotor() ? py::object(figure_dict(fe_rotor_figure(scene)))
                                     : py::object(py::none());
        return d;
    }, py::arg("scene"));
    m.def("load_scene", [](const std::string& path, const std::map<std::string, double>& overrides,
                           const std::string& motion) { return load_scene(path, overrides, motion); },
          py::arg("path"), py::arg("overrides") = std::map<std::string, double>{}, py::arg("motion") = "");

    m.def("parse_scene", &parse_scene, py::arg("text"), py::arg("origin"), py::arg("dir") = ".",
          py::arg("overrides") = std::map<std::string, double>{});
    return scene;
}
