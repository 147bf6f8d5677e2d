// The two-roller auto-balancer (balancer) and the Sommerfeld effect (sommerfeld) of a
// balancer scene file.
#include "binding_table.hpp"

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/gyrokit.hpp>

#include "common.hpp"
#include "reports.hpp"
#include "request.hpp"

#include <gyrokit/reports/balancer_reports.hpp>
#include <gyrokit/reports/sommerfeld_reports.hpp>

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

py::array_t<double> arr(const std::vector<double>& v) {
    return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

BalancerRequest balancer_request(const py::dict& kw) {
    BalancerRequest r;
    r.simulate = kw.contains("simulate") && kw["simulate"].cast<bool>();
    r.averaged = kw.contains("averaged") && kw["averaged"].cast<bool>();
    r.speed = given_number(kw, "speed");
    r.duration = given_number(kw, "duration");
    r.integrator = given_text(kw, "integrator");
    r.abs_tol = given_number(kw, "abs_tol");
    r.rel_tol = given_number(kw, "rel_tol");
    return r;
}

// A run of the equations of motion: the histories, the final state and the tables and figure of the CLI.
py::dict simulation_dict(const BalancerStudy& st, bool averaged, const std::string& title) {
    const SimulationResult& r = *st.simulation;
    py::dict d;
    d["t"] = arr(r.t);
    d["speed"] = arr(r.speed);
    d["radius"] = arr(r.radius);
    py::list alpha;
    for (const auto& a : r.alpha) alpha.append(arr(a));
    d["alpha"] = alpha;
    d["final_alpha"] = r.final_alpha;
    d["final_speed"] = r.final_speed;
    d["residual_rms"] = r.residual_rms;
    d["residual_max"] = r.residual_max;
    d["tables"] = tables_list(st.tables);
    d["figure"] = figure_dict(simulation_figure(r, averaged, title));
    return d;
}

// gk.balancer: the synchronous states and their stability per speed range, and each range's verdict;
// or a run of the equations of motion (simulate).
py::dict py_balancer(const std::string& path, const py::dict& request) {
    const BalancerScene sc = load_balancer_scene(path);
    const BalancerRequest rq = balancer_request(request);
    std::optional<BalancerStudy> study;
    {
        Released free;
        study.emplace(balancer_study(sc, rq));
    }
    if (rq.simulate) {
        // The phase histories' table on request, as the CLI's --history (the arrays are always there).
        if (!(request.contains("history") && request["history"].cast<bool>())) study->tables.erase(study->tables.begin());
        return simulation_dict(*study, rq.averaged, sc.title);
    }
    const std::vector<StateStability>& t = study->stability;
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
    for (const auto& v : study->verdicts) {
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
    d["tables"] = tables_list(study->tables);
    return d;
}

// More points than any curve needs (and than an int holds).
constexpr double kMaxSpeedPoints = 1e7;

SommerfeldRequest sommerfeld_request(const py::dict& kw) {
    SommerfeldRequest r;
    r.runup = kw.contains("runup") && kw["runup"].cast<bool>();
    if (const py::object v = given(kw, "speeds"); !v.is_none()) {
        std::vector<double> w;
        try {
            w = v.cast<std::vector<double>>();
        } catch (const py::cast_error&) {
        }
        if (w.size() != 3 || w[2] != std::floor(w[2]) || !(std::abs(w[2]) <= kMaxSpeedPoints))
            throw InputError(fmt::format("{} {}: allowed: (FROM, TO, N), nominal speeds in rad/s and a count of at most {:g}",
                                         option_noun("speeds"), py::repr(v).cast<std::string>(), kMaxSpeedPoints));
        r.speeds = SpeedRange{w[0], w[1], static_cast<int>(w[2])};
    }
    r.integrator = given_text(kw, "integrator");
    r.abs_tol = given_number(kw, "abs_tol");
    r.rel_tol = given_number(kw, "rel_tol");
    r.max_speed = given_number(kw, "max_speed");
    return r;
}

py::dict runup_dict(const SommerfeldStudy& st, const AutobalancerParameters& p, const std::string& title) {
    const RunupResult& r = *st.runup;
    py::dict d;
    d["t"] = arr(r.t);
    d["nominal"] = arr(r.nominal);
    d["rotor_speed"] = arr(r.rotor_speed);
    d["amplitude"] = arr(r.amplitude);
    d["held_rotor_speed"] = r.held_rotor_speed;
    d["held_amplitude"] = r.held_amplitude;
    d["final_rotor_speed"] = r.final_rotor_speed;
    d["tables"] = tables_list(st.tables);
    d["figure"] = figure_dict(runup_figure(p, r, title));
    return d;
}

// gk.sommerfeld: the limit speed estimate, the folds of the stationary curve and its jumps; or a run-up.
py::dict py_sommerfeld(const std::string& path, const py::dict& request) {
    const BalancerScene sc = load_balancer_scene(path);
    const SommerfeldRequest rq = sommerfeld_request(request);
    std::optional<SommerfeldStudy> study;
    {
        Released free;
        study.emplace(sommerfeld_study(sc, rq));
    }
    if (rq.runup) return runup_dict(*study, sc.params, sc.title);
    const SommerfeldAnalysis& a = study->analysis;
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
    d["tables"] = tables_list(study->tables);
    d["figure"] = figure_dict(stationary_figure(a, study->speeds, sc.title));
    return d;
}

}  // namespace

void bind_balancing(py::module_& m) {
    m.def("balancer", &py_balancer, py::arg("path"), py::arg("request"));

    m.def("sommerfeld", &py_sommerfeld, py::arg("path"), py::arg("request"));
}
