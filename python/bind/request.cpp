#include "request.hpp"

#include "common.hpp"

#include <gyrokit/core/error.hpp>

#include <pybind11/stl.h>

#include <cmath>
#include <fmt/format.h>

namespace py = pybind11;
using namespace gyrokit;

namespace gyrokit_python {

ModelArg::ModelArg(const py::object& model) {
    if (py::isinstance<Scene>(model)) {
        scene_ = &model.cast<const Scene&>();
    } else if (py::isinstance<GyroscopicSystem>(model)) {
        owned_ = scene_of(model.cast<const GyroscopicSystem&>());
        scene_ = &*owned_;
    } else {
        throw InputError(fmt::format("expected a gyrokit.System or gyrokit.Scene, got {}",
                                     py::str(py::type::of(model).attr("__name__")).cast<std::string>()));
    }
}

py::object given(const py::dict& kw, const char* name) {
    if (!kw.contains(name)) return py::none();
    return kw[name];
}

std::optional<double> given_number(const py::dict& kw, const char* name) {
    const py::object v = given(kw, name);
    if (v.is_none()) return std::nullopt;
    try {
        return v.cast<double>();
    } catch (const py::cast_error&) {
        throw InputError(fmt::format("{} {}: allowed: a number", option_field(name), py::repr(v).cast<std::string>()));
    }
}

std::optional<long long> given_count(const py::dict& kw, const char* name, const char* field, double limit) {
    const py::object v = given(kw, name);
    if (v.is_none()) return std::nullopt;
    double x = 0;
    try {
        x = v.cast<double>();
    } catch (const py::cast_error&) {
        x = std::nan("");
    }
    if (!(std::isfinite(x) && x == std::floor(x) && std::abs(x) < limit))
        throw InputError(fmt::format("{} {}: allowed: a whole number", option_field(field ? field : name),
                                     py::repr(v).cast<std::string>()));
    return static_cast<long long>(x);
}

std::optional<int> given_whole(const py::dict& kw, const char* name, const char* field) {
    const std::optional<long long> n = given_count(kw, name, field, 1e9);
    if (!n) return std::nullopt;
    return static_cast<int>(*n);
}

std::optional<std::string> given_text(const py::dict& kw, const char* name) {
    const py::object v = given(kw, name);
    if (v.is_none()) return std::nullopt;
    if (!py::isinstance<py::str>(v))
        throw InputError(fmt::format("{} {}: allowed: a name", option_field(name), py::repr(v).cast<std::string>()));
    return v.cast<std::string>();
}


RotorRequest rotor_request(const py::dict& kw) {
    RotorRequest r;
    r.unit = given_text(kw, "unit");
    if (const py::object v = given(kw, "speeds"); !v.is_none()) {
        try {
            r.speeds = v.cast<std::vector<double>>();
        } catch (const py::cast_error&) {
            throw InputError(option_field("speeds") + ": allowed: a sequence of numbers");
        }
    }
    r.modes = given_whole(kw, "modes");
    if (const py::object v = given(kw, "harmonics"); !v.is_none()) {
        std::vector<int> h;
        for (const py::handle x : v) {
            py::dict one;
            one["harmonics"] = x;
            h.push_back(*given_whole(one, "harmonics"));
        }
        r.harmonics = h;
    }
    r.f_cut = given_number(kw, "f_cut");
    r.solver = given_text(kw, "solver");
    r.method = given_text(kw, "method");
    r.target = given_number(kw, "target");
    r.target_order = given_number(kw, "target_order");
    r.lanczos = given_whole(kw, "lanczos", "lanczos_vectors");
    r.jobs = given_whole(kw, "jobs");
    return r;
}

StudyOptions resolve(const ModelArg& model, const py::dict& keywords, SpeedsNeeded speeds) {
    std::vector<std::string> notes;
    StudyOptions so = resolve_request(model.scene(), rotor_request(keywords), speeds, &notes);
    for (const auto& n : notes)
        py::module_::import("warnings").attr("warn")(spell_fields(n, keyword_words),
                                                     py::module_::import("builtins").attr("RuntimeWarning"));
    so.workers.kind = WorkerKind::Threads;   // a Python host is not forked
    return so;
}

}  // namespace gyrokit_python
