#include <gyrokit/study/transient_study.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/transient_reports.hpp>
#include <gyrokit/study/defaults.hpp>

#include <fmt/format.h>

#include <cmath>

namespace gyrokit {

namespace {

// The speed history in rad/s: a constant speed, or a run-up / run-down with its acceleration.
SpeedProfile profile_of(const TransientRequest& rq, const SpeedUnit& u) {
    const std::string speed = option_noun("speed"), run_up = option_noun("run_up"),
                      acceleration = option_noun("acceleration");
    if (rq.speed && rq.run_up)
        throw InputError(fmt::format("{} and {}: allowed: one of them (a constant speed, or a run-up or run-down)",
                                     speed, run_up));
    if (!rq.speed && !rq.run_up)
        throw InputError(fmt::format("no speed: allowed: {} (a constant speed), or {} (from, to) with {}", speed,
                                     run_up, acceleration));
    if (rq.speed) {
        if (rq.acceleration) throw InputError(fmt::format("{}: only together with {}", acceleration, run_up));
        const double w = *rq.speed / u.factor;
        return {w, w, 0.0};
    }
    const auto [from, to] = *rq.run_up;
    if (!rq.acceleration)
        throw InputError(fmt::format("{} needs {} ({}; > 0 for a run-up, < 0 for a run-down)", run_up, acceleration,
                                     u.per_second()));
    if (*rq.acceleration == 0.0)
        throw InputError(fmt::format("{} 0 {} with a {} from {:.12g} to {:.12g} {}: allowed: a finite number {} 0",
                                     option_field("acceleration"), u.per_second(), to > from ? "run-up" : "run-down",
                                     from, to, u.name, to > from ? ">" : "<"));
    SpeedProfile p{from / u.factor, to / u.factor, *rq.acceleration / u.factor};
    if (p.from == p.to)   // as a run: validate would take it for a constant speed
        throw InputError(fmt::format("{} {}:{} {}: allowed: two different finite speeds >= 0 (from:to)", option_field("run_up"), from,
                                     to, u.name));
    return p;
}

std::vector<int> outputs_of(const TransientRequest& rq, const GyroscopicSystem& sys) {
    if (!rq.dofs.empty() && rq.node)
        throw InputError(option_noun("dofs") + " and " + option_noun("node") + ": allowed: one of them");
    if (rq.node) {
        std::vector<int> out;
        const std::string node = fmt::format("{} {}", option_field("node"), *rq.node);
        try {
            out = sys.node_translations(*rq.node);
        } catch (const InputError& e) {
            throw InputError(node + ": " + e.what());
        }
        if (out.empty())
            throw InputError(node + ": no free lateral translation (a support holds it, or the model has no lateral "
                                    "DOFs); allowed: a node with free x or y");
        return out;
    }
    const std::vector<int> out = dofs_by_name(rq.dofs, sys.dofs.names, option_field("dofs"));
    return out.empty() ? transient_outputs(sys) : out;
}

// A time given: > 0 (unset is the default; 0 is not a way to ask for it).
double time_of(const std::optional<double>& t, const char* field, const char* what, const char* fallback) {
    if (!t) return 0.0;
    if (*t == 0.0)
        throw InputError(fmt::format("{} 0 s: allowed: a finite {} > 0 (s); none: {}", option_field(field), what, fallback));
    return *t;
}

}  // namespace

TransientOptions transient_options(const Scene& scene, const RotorRequest& common, const TransientRequest& rq) {
    const StudyOptions so = resolve_request(scene, common, SpeedsNeeded::No);
    const std::string start = rq.start.value_or(defaults::transient_start);
    if (start != "rest" && start != "steady")
        throw InputError(fmt::format("{} '{}': allowed: rest, steady", option_field("start"), start));
    TransientOptions o;
    o.unit = so.unit;
    o.profile = profile_of(rq, so.unit);
    o.duration = time_of(rq.duration, "duration", "time", "the ramp or 100 revolutions");
    o.dt = time_of(rq.dt, "dt", "time step",
                   "32 steps per period of the band, shorter at a constant speed where the steady response needs it");
    o.outputs = outputs_of(rq, scene.system);
    o.start_steady = start == "steady";
    o.max_steps = rq.max_steps.value_or(defaults::max_steps);
    o.kind = resolve_solver_kind(scene.dofs(), so.solver.kind);
    check_transient_options(scene.system, o);
    return o;
}

TransientStudy transient_study(const Scene& scene, const RotorRequest& common, const TransientRequest& rq) {
    TransientOptions o = transient_options(scene, common, rq);
    TransientResult r = transient_response(scene.system, o);
    const LengthUnit length = scene.length_unit();
    Table t = transient_run_table(scene.system, r, o.unit, o.start_steady, o.kind, length);
    const SpeedUnit unit = o.unit;
    return TransientStudy{unit, length, std::move(o), std::move(r), std::move(t)};
}

}  // namespace gyrokit
