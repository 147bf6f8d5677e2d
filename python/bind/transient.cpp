// Transient response by time integration (transient_response, transient_envelope,
// envelope_steady, transient_waterfall) as NumPy arrays.
#include "common.hpp"
#include "binding_table.hpp"

#include "reports.hpp"
#include "request.hpp"

#include <gyrokit/reports/transient_reports.hpp>

#include <gyrokit/analysis/transient.hpp>
#include <gyrokit/analysis/transient_signals.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/study/transient_study.hpp>

#include <fmt/format.h>

#include <array>
#include <optional>

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

// The keywords of gk.transient (None: not given) as the library's request.
TransientRequest transient_request(const py::dict& kw) {
    TransientRequest r;
    r.speed = given_number(kw, "speed");
    if (const py::object v = given(kw, "run_up"); !v.is_none()) {
        std::vector<double> w;
        try {
            w = v.cast<std::vector<double>>();
        } catch (const py::cast_error&) {
        }
        if (w.size() != 2)
            throw InputError(fmt::format("{} {}: allowed: two speeds (W0, W1)", option_field("run_up"),
                                         py::repr(v).cast<std::string>()));
        r.run_up = std::array<double, 2>{w[0], w[1]};
    }
    r.acceleration = given_number(kw, "acceleration");
    r.duration = given_number(kw, "duration");
    r.dt = given_number(kw, "dt");
    if (const py::object v = given(kw, "dofs"); !v.is_none()) {
        if (py::isinstance<py::str>(v))
            throw InputError(fmt::format("{} {}: allowed: a list of DOF names", option_field("dofs"),
                                         py::repr(v).cast<std::string>()));
        for (const py::handle d : v) {
            if (!py::isinstance<py::str>(d))
                throw InputError(fmt::format("{} {}: allowed: DOF names such as 'x12'", option_field("dofs"),
                                             py::repr(d).cast<std::string>()));
            r.dofs.push_back(d.cast<std::string>());
        }
    }
    r.node = given_whole(kw, "node");
    r.start = given_text(kw, "start");
    r.max_steps = given_count(kw, "max_steps", nullptr, 9e18);   // its range is the library's to state
    return r;
}

py::dict run(const ModelArg& model, const RotorRequest& common, const TransientRequest& rq, int windows) {
    const GyroscopicSystem& s = model.system();
    std::optional<TransientStudy> run;
    TransientEnvelope e;
    Eigen::MatrixXd at_peaks;
    {
        Released free;   // Ctrl-C stops it within a batch of steps
        run.emplace(transient_study(model.scene(), common, rq));
        e = transient_envelope(run->result, windows);
        at_peaks = envelope_steady(s, e, run->options.kind);
    }
    const TransientStudy& st = *run;
    const TransientResult& r = st.result;
    py::dict d;
    d["unit"] = st.unit.name;
    d["profile"] = py::make_tuple(r.profile.from, r.profile.to, r.profile.acceleration);
    d["t"] = array(r.t);
    d["speed"] = array(r.speed);
    d["z"] = r.z;
    std::vector<std::string> names;
    for (const int k : r.dofs) names.push_back(s.dofs.names[static_cast<std::size_t>(k)]);
    d["dofs"] = names;
    d["dt"] = r.dt;
    d["notes"] = r.notes;
    d["stats"] = py::dict(py::arg("steps") = r.stats.steps, py::arg("factorizations") = r.stats.factorizations,
                          py::arg("coefficient_updates") = r.stats.coefficient_updates,
                          py::arg("max_corrections") = r.stats.max_corrections,
                          py::arg("max_residual") = r.stats.max_residual);
    d["envelope"] = envelope_dict(e, at_peaks);
    d["tables"] = tables_list({st.table});
    d["figure"] = py::none();
    d["run"] = TransientRun{s, r, st.options.kind, st.options.start_steady, st.length};
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
    // The study of the library (transient_study): the rotor request's keywords (unit, solver) and the run's.
    m.def("transient", [](const py::object& model, const py::dict& request, const py::dict& run_keywords, int windows) {
        const ModelArg a(model);
        return run(a, rotor_request(request), transient_request(run_keywords), windows);
    }, py::arg("model"), py::arg("request"), py::arg("run"), py::arg("windows"));
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
    }, py::arg("t"), py::arg("speed"), py::arg("x"), py::arg("start_speed"), py::arg("end_speed"), py::arg("acceleration"),
          py::arg("dt"), py::arg("windows"), py::arg("frequencies"));
}
