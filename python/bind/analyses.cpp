// The rotor analyses of a System (eig, mode_shapes, campbell, critical_speeds, stability,
// pervasive, response), one named function per binding: NumPy arrays and dicts out,
// the GIL released while the library solves.
#include "binding_table.hpp"

#include <gyrokit/study/response_study.hpp>

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/gyrokit.hpp>

#include "common.hpp"
#include "frf.hpp"
#include "request.hpp"
#include "reports.hpp"

#include <gyrokit/reports/reports.hpp>

#include <fmt/format.h>
#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

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
    // The modes judged beyond the K shown (ids K + 1 on: the critical speeds and
    // stability changes may name them), speeds x those branches.
    const auto nj = static_cast<py::ssize_t>(cd.untracked.size());
    py::array_t<std::complex<double>> judged({ns, nj});
    py::array_t<int> judged_ids(nj);
    for (py::ssize_t i = 0; i < ns; ++i)
        for (py::ssize_t b = 0; b < nj; ++b) judged.mutable_at(i, b) = {nan, nan};
    for (py::ssize_t b = 0; b < nj; ++b) {
        const Branch& br = cd.untracked[static_cast<size_t>(b)];
        judged_ids.mutable_at(b) = br.id;
        for (const BranchPoint& p : br.points)
            if (const auto it = row.find(p.speed); it != row.end()) judged.mutable_at(it->second, b) = p.mode.lambda;
    }
    d["judged_eigenvalues"] = judged;
    d["judged_branches"] = judged_ids;
    return d;
}

// What the CLI prints and draws of the result, in the call's unit.
void put_reports(py::dict& d, const std::vector<Table>& tables, const std::optional<Figure>& figure = std::nullopt) {
    d["tables"] = tables_list(tables);
    d["figure"] = figure ? py::object(figure_dict(*figure)) : py::object(py::none());
}

// gk.eig: every eigenvalue at one speed (one per conjugate pair).
py::dict py_eig(const py::object& model, double speed, const py::dict& request) {
    const ModelArg m(model);
    const StudyOptions so = resolve(m, request, SpeedsNeeded::No);
    const SpeedUnit& u = so.unit;
    speed /= u.factor;
    SpectrumStudy st;
    {
        Released free;
        st = spectrum_study(m.system(), speed, so.solver, u);
    }
    py::dict d = spectrum_dict(st.spectrum);
    d["speed"] = speed;
    d["unit"] = u.name;
    put_diagnostics(d, st.diagnostics);
    put_reports(d, {eig_table(st.spectrum, speed, u)});
    return d;
}

// The shapes of a gk.modes result, kept for the figure of chosen modes (ModeShapes.plot(mode=...)).
struct ModeShapeSet {
    std::vector<ModeShape> shapes;
    double speed = 0;
    SpeedUnit unit;
    std::string title;
    LengthUnit length;
    AxisMarks marks;
    py::dict figure(const std::vector<int>& numbers) const {
        return figure_dict(mode_shape_figure(numbers.empty() ? shapes : select_mode_shapes(shapes, numbers), speed,
                                             unit, title, length, marks));
    }
};

// gk.mode_shapes: the shapes as columns, and their orbits per whirl pair (the CLI's --per node table).
py::dict py_mode_shapes(const py::object& model, double speed, const py::dict& request) {
    const ModelArg m(model);
    const GyroscopicSystem& s = m.system();
    const StudyOptions so = resolve(m, request, SpeedsNeeded::No);
    const SpeedUnit& u = so.unit;
    const LengthUnit length = m.scene().length_unit();
    // A scene's FE rotor: its disks, bearings and supports marked on the shapes.
    const AxisMarks marks = axis_marks(m.scene());
    speed /= u.factor;
    ModeShapeStudy st;
    {
        Released free;
        st = mode_shape_study(s, speed, so.solver, u);
    }
    const std::vector<ModeShape>& shapes = st.shapes;
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
    d["speed"] = speed;
    d["unit"] = u.name;
    d["dof_names"] = s.dofs.names;
    d["eigenvalues"] = lambda;
    d["shapes"] = vectors;
    d["numbers"] = number;
    d["reference"] = reference;
    d["whirl"] = whirl;
    put_diagnostics(d, st.diagnostics);
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
    const ModeShapeSet set{shapes, speed, u, m.scene().title, length, marks};
    put_reports(d,
                {mode_list_table(shapes, s.dofs.names, speed, u), mode_orbit_table(shapes, speed, u, length),
                 mode_dof_table(shapes, s.dofs.names, s.dofs.units, speed, u)},
                mode_shape_figure(shapes, speed, u, m.scene().title, length, marks));
    d["shape_set"] = set;
    return d;
}

// gk.campbell: the Campbell study, its speeds solved on threads.
py::dict py_campbell(const py::object& model, const py::dict& request) {
    const ModelArg m(model);
    const GyroscopicSystem& s = m.system();
    const StudyOptions so = resolve(m, request);
    const SpeedUnit& u = so.unit;
    const std::vector<int>& harmonics = so.harmonics;
    CampbellStudy st;
    std::vector<CriticalSpeed> cs;
    {
        Released free;
        st = campbell_study(s, so);
        cs = critical_speeds_of(s, st, so);   // the summary's and the figure's
    }
    py::dict d = campbell_dict(st.diagram);
    d["unit"] = u.name;
    put_diagnostics(d, st.diagnostics);
    std::vector<Table> tables{campbell_summary(st, cs, u, ""),
                              campbell_table(st.diagram, u)};
    for (Table& t : critical_tables(cs, u)) tables.push_back(std::move(t));
    put_reports(d, tables, campbell_figure(st.diagram, cs, harmonics, u, m.scene().title));
    return d;
}

// gk.critical_speeds: the critical speeds with their API 684 amplification factors, as columns.
py::dict py_critical_speeds(const py::object& model, const py::dict& request) {
    const ModelArg m(model);
    const StudyOptions so = resolve(m, request);
    const SpeedUnit& u = so.unit;
    CriticalSpeedStudy st;
    {
        Released free;
        st = critical_speed_study(m.system(), so);
    }
    const std::vector<CriticalSpeed>& cs = st.critical;
    const auto n = static_cast<py::ssize_t>(cs.size());
    py::array_t<double> speed(n), bound(n), damping(n), amplification(n);
    py::array_t<int> harmonic(n), branch(n);
    py::array_t<bool> critical(n);
    py::list whirl, af_method, af_dof, af_note;
    for (py::ssize_t k = 0; k < n; ++k) {
        const CriticalSpeed& c = cs[static_cast<size_t>(k)];
        speed.mutable_at(k) = c.speed;
        bound.mutable_at(k) = c.bound;
        damping.mutable_at(k) = c.mode.damping_ratio();
        harmonic.mutable_at(k) = c.harmonic;
        branch.mutable_at(k) = c.branch;
        whirl.append(to_string(c.mode.whirl));
        amplification.mutable_at(k) = c.amplification;
        af_method.append(to_string(c.amplification_method));
        af_dof.append(c.amplification_dof);
        af_note.append(c.amplification_note);
        critical.mutable_at(k) = c.api684_critical();
    }
    py::dict d;
    d["unit"] = u.name;
    d["speeds"] = speed;
    d["bounds"] = bound;
    d["harmonic"] = harmonic;
    d["branch"] = branch;
    d["whirl"] = whirl;
    d["damping_ratio"] = damping;
    d["amplification"] = amplification;
    d["af_method"] = af_method;
    d["af_dof"] = af_dof;
    d["af_note"] = af_note;
    d["api684_critical"] = critical;
    put_diagnostics(d, st.tracked.diagnostics);
    put_reports(d, critical_tables(cs, u));
    return d;
}

// gk.stability: the speeds where a mode becomes unstable or stable again.
py::dict py_stability(const py::object& model, const py::dict& request) {
    const ModelArg m(model);
    const StudyOptions so = resolve(m, request);
    const SpeedUnit& u = so.unit;
    StabilityStudy st;
    {
        Released free;
        st = stability_study(m.system(), so);
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
    d["unit"] = u.name;
    d["speeds"] = speed;
    d["bounds"] = bound;
    d["branch"] = branch;
    d["becomes_unstable"] = unstable;
    put_diagnostics(d, st.tracked.diagnostics);
    put_reports(d, {stability_table(ch, u)});
    return d;
}

// gk.pervasive: the Hautus check, one row per mode a damping component does not reach.
py::dict py_pervasive(const py::object& model, double tolerance, const py::dict& request) {
    const ModelArg m(model);
    const StudyOptions so = resolve(m, request);
    const SpeedUnit& u = so.unit;
    PervasiveStudy st;
    {
        Released free;
        st = pervasive_study(m.system(), so, tolerance);
    }
    const PervasiveReport& rep = st.report;
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
    d["unit"] = u.name;
    d["checked"] = rep.checked;
    d["checked_speeds"] = rep.speeds;
    d["checked_modes"] = rep.modes;
    d["f_cut"] = std::isfinite(rep.band) ? py::object(py::float_(rep.band)) : py::object(py::none());
    d["pervades"] = !rep.checked.empty() && rep.losses.empty();
    d["partial"] = rep.partial;
    d["damping"] = damping;
    d["speeds"] = py::array_t<double>(static_cast<py::ssize_t>(speed.size()), speed.data());
    d["mode"] = py::array_t<int>(static_cast<py::ssize_t>(mode.size()), mode.data());
    d["frequency"] = py::array_t<double>(static_cast<py::ssize_t>(frequency.size()), frequency.data());
    d["whirl"] = whirl;
    d["residual"] = py::array_t<double>(static_cast<py::ssize_t>(residual.size()), residual.data());
    put_diagnostics(d, st.diagnostics);
    put_reports(d, {pervasive_summary(rep, u), pervasive_table(rep, u)});
    return d;
}

// gk.response: the unbalance response per speed and DOF, with the CLI's stability warnings.
py::dict py_response(const py::object& model, const py::dict& request, const std::vector<int>& outputs,
                     const std::vector<std::pair<int, double>>& probe_list, bool stability_check, bool extrema,
                     bool peaks) {
    const ModelArg m(model);
    const GyroscopicSystem& s = m.system();
    const StudyOptions so = resolve(m, request);
    const SpeedUnit& u = so.unit;
    const std::string& title = m.scene().title;
    ResponseRequest rq;
    rq.length = m.scene().length_unit();
    rq.probes = probes_of(s, probe_list);
    rq.outputs = outputs;
    rq.stability_check = stability_check;
    rq.antiresonances = extrema;
    rq.peaks = peaks || extrema;
    ResponseStudy st;
    {
        Released free;
        st = response_study(s, so, rq);
    }
    py::dict d;
    d["unit"] = u.name;
    d["speeds"] = so.speeds;
    d["Z"] = st.si;   // the outputs in SI units (m, rad)
    std::vector<std::string> names;
    for (const int k : st.curve.dofs) names.push_back(st.names[static_cast<std::size_t>(k)]);
    d["names"] = names;
    put_diagnostics(d, st.diagnostics);
    // The CLI's tables: the summary with the refined peaks, the curve
    // (the peaks and antiresonances with `extrema`, as --extrema) and its Bode and polar plots.
    // The curve first (the CLI's --format csv and json; a CSV saved without a table name).
    std::vector<Table> tables{response_table(st.names, st.units, st.curve, u)};
    if (rq.peaks) tables.push_back(response_summary(st.names, st.units, st.maxima, u, 8));
    if (extrema) tables.push_back(extrema_table(st.names, st.units, st.extrema, u));
    put_reports(d, tables, response_figure(st.names, st.units, st.curve, u, title, st.plotted));
    d["polar_figure"] = figure_dict(response_polar_figure(st.names, st.units, st.curve, u, title, st.plotted));
    return d;
}

// gk.fluid: the liquid-filled rotor's critical speeds, sloshing coefficients, or a fill sweep.
py::dict py_fluid(const Scene& scene, const py::object& unit, std::optional<std::vector<double>> fill) {
    py::dict keywords;
    keywords["unit"] = unit;
    FluidRequest rq;
    rq.unit = rotor_request(keywords).unit;
    rq.fill = std::move(fill);
    FluidStudy st;
    {
        Released free;
        st = fluid_study(scene, rq);
    }
    const SpeedUnit& u = st.unit;
    py::dict d;
    d["unit"] = u.name;
    put_diagnostics(d, st.diagnostics);
    if (st.sweep) {
        const FillSweep& w = *st.sweep;
        d["fills"] = w.fills;
        py::dict by_model;
        for (const auto& [name, model] : {std::pair{"moving_undamped", LiquidModel::MovingUndamped},
                                          std::pair{"moving_damped", LiquidModel::MovingDamped},
                                          std::pair{"rigid", LiquidModel::Rigid}}) {
            py::list per_fill;
            for (const FluidCriticalSpeeds& cs : w.speeds) per_fill.append(cs.of(model));
            by_model[name] = per_fill;
        }
        d["critical_speeds"] = by_model;
        put_reports(d, {fill_sweep_table(w, u)}, fill_sweep_figure(w, u, scene.title));
        return d;
    }
    const FluidCriticalSpeeds& cs = *st.critical;
    py::dict by_model;
    by_model["moving_undamped"] = cs.moving_undamped;
    by_model["moving_damped"] = cs.moving_damped;
    by_model["rigid"] = cs.rigid;
    d["critical_speeds"] = by_model;
    d["J_eq"] = cs.J_eq;
    d["J_eq_rigid"] = cs.J_eq_rigid;
    put_reports(d, {fluid_critical_table(cs, u), sloshing_modes_table(st.rotor, cs, u), liquid_table(st.rotor, cs)});
    return d;
}

}  // namespace

void bind_analyses(py::module_& m) {
    py::class_<ModeShapeSet>(m, "_ModeShapeSet")
        .def("figure", &ModeShapeSet::figure, py::arg("numbers"),
             "the mode-shape figure of the modes numbered `numbers` (empty: all)");
    m.def("fluid", &py_fluid, py::arg("scene"), py::arg("unit"), py::arg("fill"));
    // The unit of a call's speeds and results: `unit`, else the scene's [speeds] units.
    m.def(
        "resolve_unit",
        [](const py::object& model, const py::object& unit) {
            const ModelArg a(model);
            py::dict keywords;
            keywords["unit"] = unit;   // checked as every call's keyword
            return resolve_unit(a.scene(), rotor_request(keywords).unit).name;
        },
        py::arg("model"), py::arg("unit"));
    // `request`: the keywords of rotor_request (None: not given).
    m.def("eig", &py_eig, py::arg("model"), py::arg("speed"), py::arg("request"));
    m.def("mode_shapes", &py_mode_shapes, py::arg("model"), py::arg("speed"), py::arg("request"));
    m.def("campbell", &py_campbell, py::arg("model"), py::arg("request"));
    m.def("critical_speeds", &py_critical_speeds, py::arg("model"), py::arg("request"));
    m.def("stability", &py_stability, py::arg("model"), py::arg("request"));
    m.def("pervasive", &py_pervasive, py::arg("model"), py::arg("tolerance"), py::arg("request"));
    m.def("response", &py_response, py::arg("model"), py::arg("request"), py::arg("outputs") = std::vector<int>{},
          py::arg("probes") = std::vector<std::pair<int, double>>{}, py::arg("stability_check") = true,
          py::arg("extrema") = false, py::arg("peaks") = true);
}
