// Transient response by time integration (transient_response, transient_envelope,
// envelope_steady, transient_waterfall) as NumPy arrays.
#include "common.hpp"
#include "transient.hpp"

#include "reports.hpp"

#include <gyrokit/reports/transient_reports.hpp>

#include <gyrokit/analysis/transient.hpp>
#include <gyrokit/analysis/transient_signals.hpp>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

py::array_t<double> array(const std::vector<double>& v) {
    return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::dict envelope_dict(const TransientEnvelope& e, const Eigen::MatrixXd& steady) {
    py::dict d;
    d["end"] = array(e.end);
    d["peak"] = e.peak;
    d["t"] = e.t;
    d["speed"] = e.speed;
    d["revolution"] = Eigen::MatrixXd(e.revolution.cast<double>());
    d["steady"] = steady;
    return d;
}

// A finished run kept for the pictures Python asks for later (the run-up's steady curve costs
// a thousand solves: drawn only when plotted).
struct TransientRun {
    GyroscopicSystem system;
    TransientResult result;
    SolverKind kind = SolverKind::Dense;
    bool steady_start = false;
    LengthUnit length;
};

py::dict run(const GyroscopicSystem& s, const SpeedProfile& profile, double duration, double dt,
             const std::vector<int>& outputs, bool steady, long long max_steps, const std::string& solver,
             int windows, const std::string& unit, const std::string& length_unit) {
    const SpeedUnit u = SpeedUnit::parse(unit);
    const LengthUnit length = LengthUnit::parse(length_unit);
    TransientOptions o;
    o.unit = u;
    o.profile = profile;
    o.duration = duration;
    o.dt = dt;
    o.outputs = outputs;
    o.start_steady = steady;
    o.max_steps = max_steps;
    o.kind = parse_solver_kind(solver);
    TransientResult r;
    TransientEnvelope e;
    Eigen::MatrixXd at_peaks;
    {
        Released free;   // Ctrl-C stops it within a batch of steps
        r = transient_response(s, o);
        e = transient_envelope(r, windows);
        at_peaks = envelope_steady(s, e, o.kind);
    }
    py::dict d;
    d["t"] = array(r.t);
    d["speed"] = array(r.speed);
    d["z"] = r.z;
    d["dofs"] = r.dofs;
    d["dt"] = r.dt;
    d["notes"] = r.notes;
    d["stats"] = py::dict(py::arg("steps") = r.stats.steps, py::arg("factorizations") = r.stats.factorizations,
                          py::arg("coefficient_updates") = r.stats.coefficient_updates,
                          py::arg("max_corrections") = r.stats.max_corrections,
                          py::arg("max_residual") = r.stats.max_residual);
    d["envelope"] = envelope_dict(e, at_peaks);
    d["tables"] = tables_list({transient_run_table(s, r, u, steady, o.kind, length)});
    d["figure"] = py::none();
    d["run"] = TransientRun{s, r, o.kind, steady, length};
    return d;
}

}  // namespace

void bind_transient(py::module_& m) {
    py::class_<TransientRun>(m, "_TransientRun")
        .def("figure", [](const TransientRun& t, const std::string& unit) {
            Figure f;
            {
                py::gil_scoped_release free;
                f = transient_figure(t.system, t.result, SpeedUnit::parse(unit), t.steady_start, t.kind, t.length);
            }
            return figure_dict(f);
        }, py::arg("unit"))
        .def("waterfall_figure", [](const TransientRun& t, const std::string& unit) {
            return figure_dict(
                transient_waterfall_figure(t.system, t.result, SpeedUnit::parse(unit), t.steady_start, t.length));
        }, py::arg("unit"));
    m.def("transient", [](const GyroscopicSystem& s, double from, double to, double acceleration, double duration,
                          double dt, const std::vector<int>& outputs, bool steady, long long max_steps,
                          const std::string& solver, int windows, const std::string& unit,
                          const std::string& length_unit) {
        return run(s, SpeedProfile{from, to, acceleration}, duration, dt, outputs, steady, max_steps, solver, windows,
                   unit, length_unit);
    }, py::arg("system"), py::arg("from"), py::arg("to"), py::arg("acceleration"), py::arg("duration"), py::arg("dt"),
          py::arg("outputs"), py::arg("steady"), py::arg("max_steps"), py::arg("solver"), py::arg("windows"),
          py::arg("unit") = "rad/s", py::arg("length_unit") = "m");
    // The waterfall of one recorded signal x(t) of a run with this speed history and step.
    m.def("transient_waterfall", [](const std::vector<double>& t, const std::vector<double>& speed,
                                    const Eigen::VectorXd& x, double from, double to, double acceleration, double dt,
                                    int windows, int frequencies) {
        TransientResult r;
        r.profile = {from, to, acceleration};
        r.dt = dt;
        r.t = t;
        r.speed = speed;
        r.dofs = {0};
        r.z = x;
        if (r.t.size() != static_cast<std::size_t>(x.size()) || r.speed.size() != r.t.size())
            throw InputError("waterfall: t, speed and the signal differ in length");
        Waterfall w;
        {
            py::gil_scoped_release free;
            w = transient_waterfall(r, 0, windows, frequencies);
        }
        py::dict d;
        d["t"] = array(w.t);
        d["speed"] = array(w.speed);
        d["frequencies"] = array(w.frequencies);
        d["amplitude"] = w.amplitude;
        d["window"] = w.window;
        return d;
    }, py::arg("t"), py::arg("speed"), py::arg("x"), py::arg("from"), py::arg("to"), py::arg("acceleration"),
          py::arg("dt"), py::arg("windows"), py::arg("frequencies"));
}
