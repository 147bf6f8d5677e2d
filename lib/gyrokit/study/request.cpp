#include <gyrokit/study/request.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <fmt/format.h>

#include <cmath>

namespace gyrokit {

double to_rad_s(double value, const char* field, const char* what, const SpeedUnit& u, bool positive) {
    if (!(std::isfinite(value) && (positive ? value > 0 : value >= 0)))
        throw InputError(fmt::format("{} {}: allowed: a finite {} {} 0 ({})", option_field(field), value, what,
                                     positive ? ">" : ">=", u.name));
    return value / u.factor;
}

SpeedUnit resolve_unit(const Scene& scene, const std::optional<std::string>& unit) {
    return unit ? SpeedUnit::parse(*unit) : scene.speed_unit;
}

Scene scene_of(const GyroscopicSystem& system) {
    Scene s;
    s.system = system;
    return s;
}

StudyOptions resolve_request(const Scene& scene, const RotorRequest& r, SpeedsNeeded need,
                             std::vector<std::string>* notes) {
    StudyOptions o = study_options(scene);
    o.unit = resolve_unit(scene, r.unit);
    const SpeedUnit& u = o.unit;
    if (r.speeds) {
        if (r.speeds->empty())
            throw InputError(fmt::format("{} (none): allowed: one or more finite speeds >= 0 ({})",
                                         option_field("speeds"), u.name));
        o.speeds.clear();
        for (const double w : *r.speeds) o.speeds.push_back(to_rad_s(w, "speeds", "speed", u));
    } else if (o.speeds.empty() && need == SpeedsNeeded::Yes) {
        throw InputError(fmt::format("{}no speed range; give {} ({}) or a [speeds] table in the scene",
                                     scene.path.empty() ? "" : scene.path + ": ", option_field("speeds"), u.name));
    }
    if (r.modes) {
        if (*r.modes < 0 || *r.modes > 100000)
            throw InputError(fmt::format("{} {}: allowed: 0 (every mode) to 100000, or unset (the modes in range)",
                                         option_field("modes"), *r.modes));
        o.solver.modes = *r.modes;
    }
    if (r.harmonics) {
        if (r.harmonics->empty())
            throw InputError(option_field("harmonics") + " (none): allowed: whole numbers in [1, 1000], e.g. 1 or 1,2");
        for (const int h : *r.harmonics)
            if (h < 1 || h > 1000)
                throw InputError(fmt::format("{} {}: allowed: whole numbers in [1, 1000]", option_field("harmonics"), h));
        o.harmonics = *r.harmonics;
    }
    if (r.f_cut) o.f_cut = to_rad_s(*r.f_cut, "f_cut", "frequency", u, true);
    if (r.solver) o.solver.kind = parse_solver_kind(*r.solver);
    if (r.method) {
        try {
            o.solver.eig.method = parse_eigen_method(*r.method);
        } catch (const InputError&) {
            throw InputError(fmt::format("{} '{}': allowed: auto, qz, qz-classic, state", option_field("method"), *r.method));
        }
    }
    if (r.target) o.solver.target = to_rad_s(*r.target, "target", "frequency", u);
    if (r.target_order) {
        if (!(std::isfinite(*r.target_order) && *r.target_order >= 0))
            throw InputError(fmt::format("{} {}: allowed: a finite number >= 0 (a multiple of the speed)",
                                         option_field("target_order"), *r.target_order));
        o.solver.target_order = *r.target_order;
    }
    if (r.lanczos) {
        if (*r.lanczos < 0)
            throw InputError(fmt::format("{} {}: allowed: 0 (automatic) or a count", option_field("lanczos_vectors"),
                                         *r.lanczos));
        o.solver.lanczos_vectors = *r.lanczos;
    }
    o.workers.count = worker_count(r.jobs.value_or(defaults::jobs), notes);
    return o;
}

}  // namespace gyrokit
