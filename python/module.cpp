// The compiled core of the Python package `gyrokit` (gyrokit/_core): the
// library's system, scene and analyses with NumPy/SciPy arrays in and out.
// The Python layer (gyrokit/__init__.py) adds keyword defaults from scenes,
// result classes with to_pandas() and plot().
#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/gyrokit.hpp>

#include "critical_map.hpp"
#include "frf.hpp"
#include "models.hpp"
#include "statics.hpp"

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <thread>
#include <string>

namespace py = pybind11;
using namespace gyrokit;

namespace {

// Python's keyword arguments for the library's option fields.
std::string keyword_words(const std::string& field) {
    if (field == "lanczos_vectors") return "lanczos =";
    return "";   // the others are named as in the library
}

// Notes with their option fields in Python's keywords.
std::vector<std::string> spelled(const std::vector<std::string>& notes) {
    std::vector<std::string> out;
    for (const auto& n : notes) out.push_back(spell_fields(n, keyword_words));
    return out;
}

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
        s.dof_names = dof_names.cast<std::vector<std::string>>();
    } else {
        for (int i = 0; i < n; ++i) s.dof_names.push_back("q" + std::to_string(i));
    }
    if (!whirl_pairs.is_none()) {
        s.whirl_pairs = whirl_pairs.cast<std::vector<std::pair<int, int>>>();
    } else if (n % 2 == 0) {
        for (int i = 0; i < n; i += 2) s.whirl_pairs.emplace_back(i, i + 1);   // (x, y) pairs, as a scene's default
    }
    s.validate("System");
    return s;
}

SolverOptions solver_options(const std::string& solver, int modes, const py::object& target, double target_order,
                             const std::string& method, int lanczos) {
    SolverOptions o;
    o.kind = parse_solver_kind(solver);
    o.modes = modes;
    if (!target.is_none()) o.target = target.cast<double>();
    o.target_order = target_order;
    o.eig.method = parse_eigen_method(method);
    o.lanczos_vectors = lanczos;
    return o;
}

std::vector<double> checked_speeds(const std::vector<double>& speeds) {
    if (speeds.empty()) throw InputError("speeds: empty; allowed: one or more speeds >= 0 (rad/s)");
    return speeds;
}

// One eigenvalue per conjugate pair (Im >= 0), as the CLI prints.
py::dict spectrum_dict(const QuadraticSpectrum& s) {
    const auto n = static_cast<py::ssize_t>(s.modes.size());
    py::array_t<std::complex<double>> lambda(n);
    py::array_t<double> eta(n), bound(n);
    py::list whirl, stability;
    Eigen::MatrixXcd X(s.modes.empty() ? 0 : s.modes.front().right.size(), n);
    for (py::ssize_t k = 0; k < n; ++k) {
        const Mode& m = s.modes[static_cast<size_t>(k)];
        lambda.mutable_at(k) = m.lambda;
        eta.mutable_at(k) = m.backward_error;
        bound.mutable_at(k) = m.error_bound;
        whirl.append(to_string(m.whirl));
        stability.append(to_string(m.stability()));
        X.col(k) = m.right;
    }
    py::array_t<std::complex<double>> rigid(static_cast<py::ssize_t>(s.rigid_body.size()));
    for (size_t k = 0; k < s.rigid_body.size(); ++k) rigid.mutable_at(static_cast<py::ssize_t>(k)) = s.rigid_body[k].lambda;
    py::dict d;
    d["eigenvalues"] = lambda;
    d["backward_errors"] = eta;
    d["error_bounds"] = bound;
    d["whirl"] = whirl;
    d["stability"] = stability;
    d["vectors"] = X;
    d["rigid_body"] = rigid;
    d["method"] = s.method;
    d["notes"] = spelled(s.notes);
    d["partial"] = s.partial;
    return d;
}

py::dict campbell_dict(const CampbellDiagram& cd) {
    const auto ns = static_cast<py::ssize_t>(cd.speeds.size()), nb = static_cast<py::ssize_t>(cd.branches.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    py::array_t<std::complex<double>> lambda({ns, nb});
    py::array_t<double> eta({ns, nb});
    py::list whirl;
    std::map<double, py::ssize_t> row;
    for (py::ssize_t i = 0; i < ns; ++i) row[cd.speeds[static_cast<size_t>(i)]] = i;
    std::vector<std::vector<std::string>> w(static_cast<size_t>(ns), std::vector<std::string>(static_cast<size_t>(nb)));
    for (py::ssize_t i = 0; i < ns; ++i)
        for (py::ssize_t b = 0; b < nb; ++b) lambda.mutable_at(i, b) = {nan, nan}, eta.mutable_at(i, b) = nan;
    py::array_t<int> ids(nb);
    for (py::ssize_t b = 0; b < nb; ++b) {
        const Branch& br = cd.branches[static_cast<size_t>(b)];
        ids.mutable_at(b) = br.id;
        for (const BranchPoint& p : br.points) {
            const py::ssize_t i = row.at(p.speed);
            lambda.mutable_at(i, b) = p.mode.lambda;
            eta.mutable_at(i, b) = p.mode.backward_error;
            w[static_cast<size_t>(i)][static_cast<size_t>(b)] = to_string(p.mode.whirl);
        }
    }
    py::dict d;
    d["speeds"] = py::array_t<double>(static_cast<py::ssize_t>(cd.speeds.size()), cd.speeds.data());
    d["eigenvalues"] = lambda;
    d["backward_errors"] = eta;
    d["whirl"] = w;
    d["branches"] = ids;
    d["inserted_speeds"] = cd.inserted_speeds;
    d["ambiguous_steps"] = cd.ambiguous_steps;
    d["max_backward_error"] = cd.max_backward_error;
    d["rigid_body"] = cd.rigid_body;
    d["notes"] = cd.notes;
    return d;
}

// Speeds solved in parallel on threads: a Python host must not fork.

// The library's parallelism rule; its note (jobs capped to the cores) as a Python warning.
Workers threads(int jobs) {
    std::vector<std::string> notes;
    const int count = worker_count(jobs, &notes);
    for (const auto& n : notes)
        py::module_::import("warnings").attr("warn")(spell_fields(n, keyword_words), py::module_::import("builtins").attr("RuntimeWarning"));
    return Workers{count, WorkerKind::Threads};
}

// The solver the options choose and the Campbell diagram it tracks over w (without the interpreter).
// The study every front end runs, from the call's arguments.
StudyOptions study(const SolverOptions& o, const std::vector<double>& w, const std::vector<int>& harmonics,
                   Workers workers) {
    StudyOptions so;
    so.solver = o;
    so.speeds = w;
    so.harmonics = harmonics;
    so.workers = workers;
    return so;
}

// A study's notes and warnings as the result's lists, option fields as keywords.
void put_diagnostics(py::dict& d, const Diagnostics& diagnostics) {
    py::list notes, warnings;
    for (const Diagnostic& x : diagnostics)
        (x.level == Diagnostic::Level::Warning ? warnings : notes).append(spell_fields(x.text, keyword_words));
    d["notes"] = notes;
    d["warnings"] = warnings;
}

// Whether this is Python's main thread, the one its SIGINT handler serves.
bool on_main_thread() {
    const py::object threading = py::module_::import("threading");
    return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

// The GIL released for a long call that Ctrl-C can stop: on the main thread,
// SIGINT requests an interrupt, the library notices it at its next safe point
// (between speeds, designs, ODE steps) and throws Interrupted, raised here as
// KeyboardInterrupt; one that came after the last safe point goes back to
// Python's handler when the call returns. A call from another thread leaves
// SIGINT to Python (the main thread's KeyboardInterrupt).
struct MaybeSigint {
    std::optional<InterruptOnSigint> scope;
    explicit MaybeSigint(bool on) {
        if (on) scope.emplace();
    }
};
struct Released {
    MaybeSigint sigint{on_main_thread()};   // first: it asks Python, with the GIL held
    py::gil_scoped_release free;
};

// The sweep file's study, on its own designs or on `designs` (values in the order
// of `names`; a name of the sweep keeps its tied paths).
// `scene`: a Scene's (text, name) in place of the sweep's base scene, or None.
Sweep sweep_with(const std::string& path, const py::object& scene, const py::object& names, const py::object& designs,
                 bool check_parameters = true) {
    const auto [text, name] = scene.is_none() ? std::pair<std::string, std::string>()
                                              : scene.cast<std::pair<std::string, std::string>>();
    Sweep s = read_sweep(path, text, name);
    if (designs.is_none()) return s;
    // The sweep's criteria and operating range on the given designs.
    const std::vector<SweepParameter> declared = s.parameters;
    s.parameters.clear();
    s.plot_axes.clear();
    s.sampling = Sampling::List;
    s.designs = designs.cast<std::vector<std::vector<double>>>();
    for (const auto& n : names.cast<std::vector<std::string>>()) {
        SweepParameter p;
        p.name = n;
        for (const auto& d : declared)
            if (d.name == n) p.paths = d.paths;
        s.parameters.push_back(p);
    }
    for (std::size_t j = 0; j < s.parameters.size(); ++j)
        for (const auto& d : s.designs)
            if (j < d.size()) s.parameters[j].values.push_back(d[j]);
    finalize_sweep(s, check_parameters);
    for (auto& p : s.parameters) p.values.clear();
    return s;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
    m.doc() = "gyrokit's compiled core; use the package gyrokit";
    static py::exception<Error> error(m, "Error");
    static py::exception<InputError> input_error(m, "InputError", error.ptr());
    static py::exception<SolverError> solver_error(m, "SolverError", error.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Interrupted&) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        } catch (const InputError& e) {
            PyErr_SetString(input_error.ptr(), e.message(keyword_words).c_str());
        } catch (const SolverError& e) {
            PyErr_SetString(solver_error.ptr(), e.message(keyword_words).c_str());
        } catch (const Error& e) {
            PyErr_SetString(error.ptr(), e.message(keyword_words).c_str());
        }
    });

    py::class_<GyroscopicSystem>(m, "System", "A gyroscopic system M z'' + (D + w G) z' + (K + w N + w^2 K2) z = w^2 u")
        .def(py::init(&make_from_arrays), py::arg("M"), py::arg("K"), py::arg("D") = py::none(),
             py::arg("G") = py::none(), py::arg("N") = py::none(), py::arg("K2") = py::none(),
             py::arg("damping") = py::dict(), py::arg("unbalance") = py::none(), py::arg("dof_names") = py::none(),
             py::arg("whirl_pairs") = py::none())
        .def_property_readonly("size", &GyroscopicSystem::size)
        .def_property_readonly("dof_names", [](const GyroscopicSystem& s) { return s.dof_names; })
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
        .def_readonly("model_type", &Scene::model_type)
        .def_readonly("system", &Scene::system)
        .def_readonly("modes", &Scene::modes)
        .def_readonly("harmonics", &Scene::harmonics)
        .def_readonly("target_order", &Scene::target_order)
        .def_property_readonly("target", [](const Scene& s) { return s.target; })
        .def_property_readonly("solver", [](const Scene& s) { return to_string(s.solver); })
        .def_property_readonly("speeds", [](const Scene& s) -> py::object {
            if (!s.speeds) return py::none();
            const std::vector<double> p = s.speeds->points();
            return py::array_t<double>(static_cast<py::ssize_t>(p.size()), p.data());
        });
    bind_models(m, scene);
    bind_statics(m);
    bind_critical_map(m);
    bind_frf(m);

    m.def("load_scene", [](const std::string& path, const std::map<std::string, double>& overrides,
                           const std::string& motion) { return load_scene(path, overrides, motion); },
          py::arg("path"), py::arg("overrides") = std::map<std::string, double>{}, py::arg("motion") = "");

    m.def("eig", [](const GyroscopicSystem& s, double speed, const std::string& solver, int modes,
                    const py::object& target, double target_order, const std::string& method, int lanczos) {
        if (!(std::isfinite(speed) && speed >= 0))
            throw InputError("speed = " + std::to_string(speed) + ": allowed: a finite number >= 0 (rad/s)");
        const SolverOptions o = solver_options(solver, modes, target, target_order, method, lanczos);
        QuadraticSpectrum sp;
        {
            Released free;
            sp = choose_solver(s, o).make()(speed);
        }
        return spectrum_dict(sp);
    }, py::arg("system"), py::arg("speed"), py::arg("solver"), py::arg("modes"), py::arg("target"),
          py::arg("target_order"), py::arg("method"), py::arg("lanczos"));

    m.def("mode_shapes", [](const GyroscopicSystem& s, double speed, const std::string& solver, int modes,
                            const py::object& target, double target_order, const std::string& method, int lanczos) {
        if (!(std::isfinite(speed) && speed >= 0))
            throw InputError("speed = " + std::to_string(speed) + ": allowed: a finite number >= 0 (rad/s)");
        const SolverOptions o = solver_options(solver, modes, target, target_order, method, lanczos);
        std::vector<ModeShape> shapes;
        std::vector<std::string> notes;
        {
            Released free;
            shapes = mode_shapes(s, speed, o, &notes);
        }
        const auto k = static_cast<Eigen::Index>(shapes.size());
        Eigen::VectorXcd lambda(k);
        Eigen::MatrixXcd vectors(s.size(), k);
        std::vector<int> number, reference;
        std::vector<std::string> whirl;
        // Orbits: one row per mode and whirl pair, as the CLI's --per node table.
        std::vector<int> orbit_mode, orbit_node;
        std::vector<std::string> orbit_pair, orbit_unit, orbit_whirl;
        std::vector<double> orbit_z, major, minor, angle, phase;
        for (Eigen::Index j = 0; j < k; ++j) {
            const ModeShape& m = shapes[static_cast<size_t>(j)];
            lambda(j) = m.mode.lambda;
            vectors.col(j) = m.shape;
            number.push_back(m.number);
            reference.push_back(m.reference);
            whirl.push_back(to_string(m.mode.whirl));
            for (const PairOrbit& p : m.orbits) {
                orbit_mode.push_back(m.number);
                orbit_pair.push_back(p.name);
                orbit_unit.push_back(p.unit);
                orbit_node.push_back(p.node);
                orbit_z.push_back(p.z);
                major.push_back(p.orbit.major);
                minor.push_back(p.orbit.minor);
                angle.push_back(p.orbit.angle);
                phase.push_back(p.orbit.phase);
                orbit_whirl.push_back(to_string(p.orbit.whirl));
            }
        }
        py::dict d;
        d["eigenvalues"] = lambda;
        d["shapes"] = vectors;
        d["numbers"] = number;
        d["reference"] = reference;
        d["whirl"] = whirl;
        d["notes"] = spelled(notes);
        py::dict orbits;
        orbits["mode"] = orbit_mode;
        orbits["pair"] = orbit_pair;
        orbits["unit"] = orbit_unit;
        orbits["node"] = orbit_node;
        orbits["z"] = orbit_z;
        orbits["major"] = major;
        orbits["minor"] = minor;
        orbits["angle"] = angle;
        orbits["phase"] = phase;
        orbits["whirl"] = orbit_whirl;
        d["orbits"] = orbits;
        return d;
    }, py::arg("system"), py::arg("speed"), py::arg("solver"), py::arg("modes"), py::arg("target"),
          py::arg("target_order"), py::arg("method"), py::arg("lanczos"));

    m.def("campbell", [](const GyroscopicSystem& s, const std::vector<double>& speeds,
                         const std::vector<int>& harmonics, const std::string& solver, int modes,
                         const py::object& target, double target_order, const std::string& method, int lanczos,
                         int jobs) {
        const SolverOptions o = solver_options(solver, modes, target, target_order, method, lanczos);
        const std::vector<double> w = checked_speeds(speeds);
        const Workers workers = threads(jobs);
        CampbellStudy st;
        {
            Released free;
            st = campbell_study(s, study(o, w, harmonics, workers));
        }
        py::dict d = campbell_dict(st.diagram);
        put_diagnostics(d, st.diagnostics);
        return d;
    }, py::arg("system"), py::arg("speeds"), py::arg("harmonics"), py::arg("solver"), py::arg("modes"), py::arg("target"),
          py::arg("target_order"), py::arg("method"), py::arg("lanczos"), py::arg("jobs"));

    m.def("critical_speeds", [](const GyroscopicSystem& s, const std::vector<double>& speeds,
                                const std::vector<int>& harmonics, const std::string& solver, int modes,
                                const py::object& target, double target_order, const std::string& method, int lanczos,
                                int jobs) {
        const SolverOptions o = solver_options(solver, modes, target, target_order, method, lanczos);
        const std::vector<double> w = checked_speeds(speeds);
        const Workers workers = threads(jobs);
        for (int h : harmonics)
            if (h < 1) throw InputError("harmonics: " + std::to_string(h) + " is not allowed; allowed: whole numbers >= 1");
        CriticalSpeedStudy st;
        {
            Released free;
            st = critical_speed_study(s, study(o, w, harmonics, workers));
        }
        const std::vector<CriticalSpeed>& cs = st.critical;
        const auto n = static_cast<py::ssize_t>(cs.size());
        py::array_t<double> speed(n), damping(n), amplification(n);
        py::array_t<int> harmonic(n), branch(n);
        py::array_t<bool> critical(n);
        py::list whirl, af_method;
        for (py::ssize_t k = 0; k < n; ++k) {
            const CriticalSpeed& c = cs[static_cast<size_t>(k)];
            speed.mutable_at(k) = c.speed;
            damping.mutable_at(k) = c.mode.damping_ratio();
            harmonic.mutable_at(k) = c.harmonic;
            branch.mutable_at(k) = c.branch;
            whirl.append(to_string(c.mode.whirl));
            amplification.mutable_at(k) = c.amplification;
            af_method.append(to_string(c.amplification_method));
            critical.mutable_at(k) = c.api684_critical();
        }
        py::dict d;
        d["speeds"] = speed;
        d["harmonic"] = harmonic;
        d["branch"] = branch;
        d["whirl"] = whirl;
        d["damping_ratio"] = damping;
        d["amplification"] = amplification;
        d["af_method"] = af_method;
        d["api684_critical"] = critical;
        put_diagnostics(d, st.tracked.diagnostics);
        return d;
    }, py::arg("system"), py::arg("speeds"), py::arg("harmonics"), py::arg("solver"), py::arg("modes"),
          py::arg("target"), py::arg("target_order"), py::arg("method"), py::arg("lanczos"), py::arg("jobs"));

    m.def("stability", [](const GyroscopicSystem& s, const std::vector<double>& speeds,
                          const std::vector<int>& harmonics, const std::string& solver, int modes,
                          const py::object& target, double target_order, const std::string& method, int lanczos,
                          int jobs) {
        const SolverOptions o = solver_options(solver, modes, target, target_order, method, lanczos);
        const std::vector<double> w = checked_speeds(speeds);
        const Workers workers = threads(jobs);
        StabilityStudy st;
        {
            Released free;
            st = stability_study(s, study(o, w, harmonics, workers));
        }
        const std::vector<StabilityChange>& ch = st.changes;
        const auto n = static_cast<py::ssize_t>(ch.size());
        py::array_t<double> speed(n), bound(n);
        py::array_t<int> branch(n);
        py::array_t<bool> unstable(n);
        for (py::ssize_t k = 0; k < n; ++k) {
            speed.mutable_at(k) = ch[static_cast<size_t>(k)].speed;
            bound.mutable_at(k) = ch[static_cast<size_t>(k)].bound;
            branch.mutable_at(k) = ch[static_cast<size_t>(k)].branch;
            unstable.mutable_at(k) = ch[static_cast<size_t>(k)].becomes_unstable;
        }
        py::dict d;
        d["speeds"] = speed;
        d["bounds"] = bound;
        d["branch"] = branch;
        d["becomes_unstable"] = unstable;
        put_diagnostics(d, st.tracked.diagnostics);
        return d;
    }, py::arg("system"), py::arg("speeds"), py::arg("harmonics"), py::arg("solver"), py::arg("modes"),
          py::arg("target"), py::arg("target_order"), py::arg("method"), py::arg("lanczos"), py::arg("jobs"));

    m.def("parse_scene", &parse_scene, py::arg("text"), py::arg("origin"), py::arg("dir") = ".",
          py::arg("overrides") = std::map<std::string, double>{});

    m.def("pervasive", [](const GyroscopicSystem& s, const std::vector<double>& speeds, double tolerance,
                          const std::string& solver, int modes, const py::object& target, double target_order,
                          const std::string& method, int lanczos, int jobs) {
        if (!(tolerance > 0.0 && tolerance < 1.0))
            throw InputError("tolerance = " + std::to_string(tolerance) + ": allowed: 0 < tolerance < 1");
        PervasiveOptions po;
        po.tolerance = tolerance;
        po.modes = modes;
        po.solver = solver_options(solver, modes, target, target_order, method, lanczos);
        po.threads = threads(jobs);
        const std::vector<double> w = checked_speeds(speeds);
        PervasiveReport rep;
        {
            Released free;
            rep = pervasive_damping(s, w, po);
        }
        py::list damping, whirl;
        std::vector<double> speed, frequency, residual;
        std::vector<int> mode;
        for (const auto& l : rep.losses) {
            damping.append(l.damping);
            whirl.append(to_string(l.lost.whirl));
            speed.push_back(l.speed);
            frequency.push_back(l.lost.frequency());
            residual.push_back(l.residual);
            mode.push_back(l.mode);
        }
        py::dict d;
        d["checked"] = rep.checked;
        d["damping"] = damping;
        d["speeds"] = py::array_t<double>(static_cast<py::ssize_t>(speed.size()), speed.data());
        d["mode"] = py::array_t<int>(static_cast<py::ssize_t>(mode.size()), mode.data());
        d["frequency"] = py::array_t<double>(static_cast<py::ssize_t>(frequency.size()), frequency.data());
        d["whirl"] = whirl;
        d["residual"] = py::array_t<double>(static_cast<py::ssize_t>(residual.size()), residual.data());
        return d;
    }, py::arg("system"), py::arg("speeds"), py::arg("tolerance"), py::arg("solver"), py::arg("modes"),
          py::arg("target"), py::arg("target_order"), py::arg("method"), py::arg("lanczos"), py::arg("jobs"));

    m.def("response", [](const GyroscopicSystem& s, const std::vector<double>& speeds, const std::vector<int>& harmonics,
                         const std::string& solver, int modes, const py::object& target, double target_order) {
        const std::vector<double> w = checked_speeds(speeds);
        const SolverOptions o = solver_options(solver, modes, target, target_order, "qz", 0);
        const SolverKind kind = resolve_solver_kind(s.size(), o.kind);
        Eigen::MatrixXcd Z(static_cast<Eigen::Index>(w.size()), s.size());
        Diagnostics warnings;
        {
            Released free;
            s.validate("response: the system");
            for (std::size_t i = 0; i < w.size(); ++i) {
                throw_if_interrupted();
                Z.row(static_cast<Eigen::Index>(i)) = unbalance_response(s, w[i], kind).transpose();
            }
            // The CLI's check: where a mode is unstable, the response is no steady state.
            warnings = response_stability_warnings(s, study(o, w, harmonics, Workers{1, WorkerKind::Threads}));
        }
        py::dict d;
        d["Z"] = Z;
        put_diagnostics(d, warnings);
        return d;
    }, py::arg("system"), py::arg("speeds"), py::arg("harmonics"), py::arg("solver"), py::arg("modes"),
          py::arg("target"), py::arg("target_order"));

    m.def("screen", [](const std::string& path, const py::object& scene, const py::object& names,
                       const py::object& designs, int jobs, const py::object& progress) {
        const Sweep s = sweep_with(path, scene, names, designs);
        RunOptions o;
        o.jobs = threads(jobs).count;
        if (!progress.is_none())
            o.progress = [progress](std::size_t done, std::size_t total) {
                py::gil_scoped_acquire hold;
                progress(done, total);
            };
        RunResult r;
        {
            Released free;
            r = run_screening(s, o);
        }
        std::vector<std::vector<std::string>> rows;
        for (const auto& row : r.rows) rows.push_back(row.cells);
        py::dict d;
        d["columns"] = r.columns;
        d["rows"] = rows;
        d["parameters"] = [&] {
            std::vector<std::string> p;
            for (const auto& x : s.parameters) p.push_back(x.name);
            return p;
        }();
        d["quantities"] = quantity_columns(s);
        d["labels"] = label_columns(s);
        d["unit"] = s.unit.name;
        return d;
    }, py::arg("sweep"), py::arg("scene"), py::arg("names"), py::arg("designs"), py::arg("jobs"), py::arg("progress"));

    // One design of the study, for a caller's executor (a process pool, a Dask
    // cluster): the row run_screening would write for it.
    // `number`: the design's number in the caller's study (designs given one by one
    // are design 0 of a one-design list).
    m.def("screen_design", [](const std::string& path, const py::object& scene, const py::object& names,
                              const py::object& designs, std::size_t index, std::size_t number) {
        const Sweep s = sweep_with(path, scene, names, designs, false);
        if (index >= s.design_count())
            throw InputError("design " + std::to_string(index) + ": allowed: 0 to " +
                             std::to_string(s.design_count() == 0 ? 0 : s.design_count() - 1));
        DesignResult r;
        {
            Released free;
            r = evaluate_design(s, index);
        }
        r.index = number;
        return format_row(s, r).cells;
    }, py::arg("sweep"), py::arg("scene"), py::arg("names"), py::arg("designs"), py::arg("index"), py::arg("number"));

    // What a study is before it runs: its columns, parameters, quantities, unit and design count.
    m.def("screen_plan", [](const std::string& path, const py::object& scene, const py::object& names,
                            const py::object& designs) {
        const Sweep s = sweep_with(path, scene, names, designs);
        py::dict d;
        d["columns"] = result_columns(s);
        std::vector<std::string> p;
        for (const auto& x : s.parameters) p.push_back(x.name);
        d["parameters"] = p;
        d["quantities"] = quantity_columns(s);
        d["labels"] = label_columns(s);
        d["unit"] = s.unit.name;
        d["designs"] = s.design_count();
        return d;
    }, py::arg("sweep"), py::arg("scene"), py::arg("names"), py::arg("designs"));

    // The row of a design that could not be evaluated where it ran (a worker lost):
    // verdict error with `reason`, so that no design is silently missing.
    m.def("screen_error_row", [](const std::string& path, const py::object& scene, const py::object& names,
                                 const py::object& designs, std::size_t index, std::size_t number,
                                 const std::string& reason) {
        const Sweep s = sweep_with(path, scene, names, designs, false);
        DesignResult r;
        r.index = number;
        r.parameters = s.design(index);
        r.quantities.assign(quantity_columns(s).size(), std::nullopt);
        r.labels.assign(label_columns(s).size(), std::string());
        r.verdict = Verdict::Error;
        r.reason = reason;
        return format_row(s, r).cells;
    }, py::arg("sweep"), py::arg("scene"), py::arg("names"), py::arg("designs"), py::arg("index"),
          py::arg("number"), py::arg("reason"));

    m.def("balancer", [](const std::string& path) {
        const BalancerScene sc = load_balancer_scene(path);
        std::vector<StateStability> t;
        {
            Released free;
            t = stability_table(sc.params);
        }
        py::list state, alpha, range, stable, stable_eigen;
        std::vector<double> from, to, re;
        std::vector<int> compensating;
        for (const auto& r : t) {
            state.append(r.state.label);
            alpha.append(r.state.alpha);
            range.append(r.range.name);
            from.push_back(r.range.from);
            to.push_back(r.range.to);
            stable.append(r.stable_criterion);
            stable_eigen.append(r.stable_eigen);
            re.push_back(r.max_real_eigenvalue);
            compensating.push_back(r.state.compensating);
        }
        const auto arr = [](const std::vector<double>& v) { return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data()); };
        py::dict d;
        d["state"] = state;
        d["alpha"] = alpha;
        d["range"] = range;
        d["range_from"] = arr(from);
        d["range_to"] = arr(to);
        d["stable"] = stable;
        d["stable_eigen"] = stable_eigen;
        d["max_real_eigenvalue"] = arr(re);
        d["compensating"] = compensating;
        py::list ranges;
        for (const auto& v : range_verdicts(t)) {
            py::dict x;
            x["range"] = v.range.name;
            x["from"] = v.range.from;
            x["to"] = v.range.to;
            x["balances"] = v.balances();
            x["stable_compensating"] = v.compensating;
            x["stable_other"] = v.other;
            x["disputed"] = v.disputed;
            ranges.append(x);
        }
        d["ranges"] = ranges;
        return d;
    }, py::arg("path"));

    m.def("sommerfeld", [](const std::string& path) {
        const BalancerScene sc = load_balancer_scene(path);
        SommerfeldAnalysis a;
        {
            Released free;
            a = analyse_sommerfeld(sc.params);
        }
        py::dict d;
        d["limit_speed_estimate"] = a.estimate;
        d["has_jump"] = a.has_jump;
        py::list folds;
        for (const auto& f : a.folds) {
            py::dict x;
            x["kind"] = f.maximum ? "maximum" : "minimum";
            x["nominal"] = f.point.nominal;
            x["rotor_speed"] = f.point.rotor_speed;
            x["roller_speed"] = f.point.roller_speed;
            folds.append(x);
        }
        d["folds"] = folds;
        if (a.has_jump) {
            d["jump_up"] = a.jump_up.point.nominal;
            d["jump_up_rotor_speed"] = a.jump_up.point.rotor_speed;
            d["jump_down"] = a.jump_down.point.nominal;
            d["jump_down_rotor_speed"] = a.jump_down.point.rotor_speed;
        }
        return d;
    }, py::arg("path"));

    m.attr("__version__") = GYROKIT_VERSION;
}
