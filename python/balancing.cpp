// The two-roller auto-balancer (balancer) and the Sommerfeld effect (sommerfeld) of a
// balancer scene file.
#include "balancing.hpp"

#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/gyrokit.hpp>

#include "common.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

// gk.balancer: the synchronous states and their stability per speed range, and each range's verdict.
py::dict py_balancer(const std::string& path) {
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
}

// gk.sommerfeld: the limit speed estimate, the folds of the stationary curve and its jumps.
py::dict py_sommerfeld(const std::string& path) {
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
}

}  // namespace

void bind_balancing(py::module_& m) {
    m.def("balancer", &py_balancer, py::arg("path"));

    m.def("sommerfeld", &py_sommerfeld, py::arg("path"));
}
