#include <gyrokit/study/balancer_study.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/balancer_reports.hpp>

#include <fmt/format.h>

#include <cmath>

namespace gyrokit {

namespace {

void check_tolerances(const OdeOptions& ode) {
    if (!(ode.abs_tol > 0.0 && ode.abs_tol < 1.0) || !(ode.rel_tol > 0.0 && ode.rel_tol < 1.0))
        throw InputError(fmt::format("{} {} / {} {}: allowed: 0 < tolerance < 1", option_field("abs_tol"), ode.abs_tol,
                                     option_field("rel_tol"), ode.rel_tol));
}

}  // namespace

OdeMethod integrator_of(const std::string& name) {
    try {
        return parse_ode_method(name);
    } catch (const InputError& e) {   // its range, under the field's name
        const std::string text = e.what();
        const std::size_t allowed = text.find("allowed: ");
        throw InputError(fmt::format("{} '{}': {}", option_field("integrator"), name,
                                     allowed == std::string::npos ? text : text.substr(allowed)));
    }
}

BalancerStudy balancer_plan(const BalancerScene& sc, const BalancerRequest& rq) {
    BalancerStudy st;
    st.params = sc.params;
    if (!rq.simulate) {
        if (rq.averaged || rq.speed || rq.duration || rq.integrator || rq.abs_tol || rq.rel_tol)
            throw InputError(fmt::format("{}, {}, {}, {}, {} and {} need {}", option_noun("averaged"),
                                         option_noun("speed"), option_noun("duration"), option_noun("integrator"),
                                         option_noun("abs_tol"), option_noun("rel_tol"), option_noun("simulate")));
        return st;
    }
    AutobalancerParameters& p = st.params;
    if (rq.speed) {
        if (!(*rq.speed > 0.0) || !std::isfinite(*rq.speed))
            throw InputError(fmt::format("{} {}: allowed: a finite number > 0 (rad/s)", option_field("speed"), *rq.speed));
        p.drive = Drive::PrescribedSpeed;
        p.speed = *rq.speed;
    }
    if (!sc.has_simulation)
        throw InputError(fmt::format("{}: {} needs a [simulation] table (duration, alpha1, alpha2)", sc.file,
                                     option_noun("simulate")));
    // Without bearing damping the free vibration never decays and no state is stationary.
    if (!(p.c_x > 0.0) || !(p.c_y > 0.0))
        throw InputError(fmt::format("{}: [model] c_x = {}, c_y = {}: the simulation needs bearing damping c_x, c_y > 0 "
                                     "N s/m", sc.file, p.c_x, p.c_y));
    SimulationSettings& s = st.settings;
    s = sc.simulation;
    if (rq.duration) {
        if (!(*rq.duration > 0.0) || !std::isfinite(*rq.duration))
            throw InputError(fmt::format("{} {}: allowed: a finite number > 0 (s)", option_field("duration"), *rq.duration));
        s.duration = *rq.duration;
    }
    if (rq.integrator) s.ode.method = integrator_of(*rq.integrator);
    if (rq.abs_tol) s.ode.abs_tol = *rq.abs_tol;
    if (rq.rel_tol) s.ode.rel_tol = *rq.rel_tol;
    check_tolerances(s.ode);
    if (rq.averaged && p.drive != Drive::PrescribedSpeed)
        throw InputError(fmt::format("{}: the slow-phase equations need a prescribed speed (give {})",
                                     option_noun("averaged"), option_noun("speed")));
    return st;
}

BalancerStudy balancer_study(const BalancerScene& sc, const BalancerRequest& rq, std::function<void(double)> progress) {
    BalancerStudy st = balancer_plan(sc, rq);
    if (!rq.simulate) {
        st.stability = state_stability_ranges(st.params);
        st.verdicts = range_verdicts(st.stability);
        st.tables = {synchronous_states_table(st.params, st.stability), balancing_ranges_table(st.verdicts)};
        return st;
    }
    st.settings.ode.progress = std::move(progress);
    const AutobalancerParameters& p = st.params;
    st.simulation = rq.averaged ? simulate_averaged(p, st.settings) : simulate(p, st.settings);
    const SimulationResult& r = *st.simulation;
    st.tables = {simulation_history_table(r),
                 simulation_final_table(st.settings, r, rq.averaged, nearest_stable_state(p, r.final_speed, r.final_alpha))};
    return st;
}

}  // namespace gyrokit
