#include <gyrokit/study/sommerfeld_study.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/sommerfeld_reports.hpp>
#include <gyrokit/study/balancer_study.hpp>

#include <fmt/format.h>

#include <cmath>
#include <optional>

namespace gyrokit {

SommerfeldStudy sommerfeld_plan(const BalancerScene& sc, const SommerfeldRequest& rq) {
    SommerfeldStudy st;
    if (!rq.runup) {
        if (rq.integrator || rq.abs_tol || rq.rel_tol || rq.max_speed)
            throw InputError(fmt::format("{}, {}, {} and {} need {}", option_noun("integrator"), option_noun("abs_tol"),
                                         option_noun("rel_tol"), option_noun("max_speed"), option_noun("runup")));
        if (rq.speeds) rq.speeds->validate(option_noun("speeds"));
        return st;
    }
    if (rq.speeds)
        throw InputError(fmt::format("{} sets the stationary curves; not with {}", option_noun("speeds"),
                                     option_noun("runup")));
    const std::optional<OdeMethod> method = rq.integrator ? std::optional(integrator_of(*rq.integrator)) : std::nullopt;
    if (!sc.has_runup)
        throw InputError(fmt::format("{}: {} needs a [runup] table (max_speed, rise, hold, fall)", sc.file,
                                     option_noun("runup")));
    RunupSettings& s = st.settings;
    s = sc.runup;
    if (method) s.ode.method = *method;
    if (rq.abs_tol) s.ode.abs_tol = *rq.abs_tol;
    if (rq.rel_tol) s.ode.rel_tol = *rq.rel_tol;
    if (rq.max_speed) s.max_speed = *rq.max_speed;
    if (!(s.ode.abs_tol > 0.0 && s.ode.abs_tol < 1.0) || !(s.ode.rel_tol > 0.0 && s.ode.rel_tol < 1.0))
        throw InputError(fmt::format("{} {} / {} {}: allowed: 0 < tolerance < 1", option_field("abs_tol"),
                                     s.ode.abs_tol, option_field("rel_tol"), s.ode.rel_tol));
    if (!(s.max_speed > 0.0) || !std::isfinite(s.max_speed))
        throw InputError(fmt::format("{} {}: allowed: a finite number > 0 (rad/s)", option_field("max_speed"), s.max_speed));
    return st;
}

SommerfeldStudy sommerfeld_study(const BalancerScene& sc, const SommerfeldRequest& rq,
                                 std::function<void(double)> progress) {
    SommerfeldStudy st = sommerfeld_plan(sc, rq);
    const AutobalancerParameters& p = sc.params;
    if (rq.runup) {
        sommerfeld_system(p);   // the summary's analysis: reject unsuitable scenes before the run
        st.settings.ode.progress = std::move(progress);
        st.runup = simulate_runup(p, st.settings);
        st.summary = summarize_runup(p, *st.runup);
        st.tables = {runup_history_table(*st.runup), runup_summary_table(st.settings, *st.runup, *st.summary)};
        return st;
    }
    st.analysis = analyse_sommerfeld(p);
    st.speeds = rq.speeds ? *rq.speeds : stationary_speeds(p, st.analysis);
    st.tables = {stationary_states_table(st.analysis, st.speeds), folds_table(st.analysis),
                 sommerfeld_summary_table(p, st.analysis)};
    return st;
}

}  // namespace gyrokit
