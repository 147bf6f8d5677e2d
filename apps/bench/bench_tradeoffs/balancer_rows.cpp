// gyrokit-bench-tradeoffs: the rows of the auto-balancer and the Sommerfeld
// run-up. ODE method and tolerance of the full equations (area "balancer"),
// averaged equations and stationary states against the full equations (area
// "averaged").
#include "tradeoffs.hpp"

#include <gyrokit/balancing/sommerfeld.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <string>
#include <vector>

using namespace gyrokit;
using namespace gyrokit::bench;

namespace tradeoffs {

// ---------------------------------------------------------------------------
// 5. Auto-balancer ODE, averaged equations

void balancer_rows(Table& t, const Settings& s) {
    struct Setting {
        OdeMethod method;
        double tol;
    };
    const std::vector<Setting> settings =
        s.quick ? std::vector<Setting>{{OdeMethod::Rk8pd, 1e-6}, {OdeMethod::Rk8pd, 1e-10}}
                : std::vector<Setting>{{OdeMethod::Rk8pd, 1e-6},  {OdeMethod::Rk8pd, 1e-8},  {OdeMethod::Rk8pd, 1e-10},
                                       {OdeMethod::Rk8pd, 1e-12}, {OdeMethod::Rkf45, 1e-6},  {OdeMethod::Rkf45, 1e-10},
                                       {OdeMethod::Msbdf, 1e-8}};
    for (const std::string name : {"bild9", "bild10"}) {
        const BalancerScene sc = load_data_balancer_scene("balancer_" + name + ".toml");
        const SimulationResult r0 = balancer_reference(sc);
        for (const Setting& st : settings) {
            const bool def = st.method == OdeMethod::Rk8pd && st.tol == 1e-10;
            Trade r{"balancer", "auto-balancer " + name + ", full equations (18)", "ODE method / tolerance",
                    fmt::format("{} {:g}{}", ode_method_name(st.method), st.tol, def ? " (default)" : ""),
                    std::string("-"), std::string("-"), "final phases, deg", "rk8pd, tol 1e-13", ""};
            try {
                SimulationResult res;
                r.seconds = s.time([&] { res = run_balancer(sc, false, st.method, st.tol); });
                r.error = final_phase_error(res, r0) * 180 / kPi;
                r.note = fmt::format("{} steps", res.stats.steps);
            } catch (const Error& e) {
                r.note = failure(e);
            }
            add(t, r);
        }
    }
}

void averaged_rows(Table& t, const Settings& s) {
    // Auto-balancer: averaged slow-phase equations and their stationary state vs the full equations.
    for (const std::string name : {"bild9", "bild10"}) {
        const BalancerScene sc = load_data_balancer_scene("balancer_" + name + ".toml");
        const SimulationResult r0 = balancer_reference(sc);
        const std::string model = "auto-balancer " + name, reference = "full (18), rk8pd, tol 1e-13";
        SimulationResult full, avg;
        const double t_full = s.time([&] { full = run_balancer(sc, false, OdeMethod::Rk8pd, 1e-10); });
        const double t_avg = s.time([&] { avg = run_balancer(sc, true, OdeMethod::Rk8pd, 1e-10); });
        add(t, {"averaged", model, "equations", "full (18), rk8pd 1e-10", t_full,
                final_phase_error(full, r0) * 180 / kPi, "final phases, deg", reference,
                fmt::format("{} steps", full.stats.steps)});
        add(t, {"averaged", model, "equations", "averaged slow-phase, rk8pd 1e-10", t_avg,
                final_phase_error(avg, r0) * 180 / kPi, "final phases, deg", reference,
                fmt::format("{} steps", avg.stats.steps)});
        // The stationary state of the damped slow equations, started from the
        // synchronous state nearest to where the full run ends.
        const double speed = sc.params.reference_speed();
        SynchronousState near;
        double best = std::numeric_limits<double>::infinity();
        for (const SynchronousState& st : synchronous_states(sc.params)) {
            double dist = 0.0;
            for (size_t i = 0; i < st.alpha.size(); ++i)
                dist = std::max(dist, phase_distance(st.alpha[i], r0.final_alpha[i]));
            if (dist < best) best = dist, near = st;
        }
        SimulationResult eq;
        const double t_eq = s.time([&] { eq.final_alpha = damped_equilibrium(sc.params, speed, near.alpha); });
        add(t, {"averaged", model, "equations", fmt::format("stationary slow-phase state ({})", near.label), t_eq,
                final_phase_error(eq, r0) * 180 / kPi, "final phases, deg", reference, "Newton on V_i = 0"});
    }
    // Sommerfeld run-ups: the speeds held after the run-up vs the stationary curves.
    for (const std::string name : {"rotor", "two_rollers_unbalance"}) {
        const BalancerScene sc = load_data_balancer_scene("sommerfeld_" + name + ".toml");
        const RunupSettings ref = sommerfeld_reference_settings(sc);
        const RunupResult r0 = simulate_runup(sc.params, ref);
        const bool rollers = !sc.params.rollers.empty();
        const auto held_error = [&](double rotor, double roller) {
            double e = std::fabs(rotor / r0.held_rotor_speed - 1.0);
            if (rollers) e = std::max(e, std::fabs(roller / r0.held_roller_speed - 1.0));
            return e;
        };
        const std::string model = "Sommerfeld run-up " + name, reference = "full (7), rk8pd, tol 1e-12";
        const std::string error_of = rollers ? "rel. held rotor and roller speed" : "rel. held rotor speed";
        RunupSettings def = ref;
        def.ode = sc.runup.ode;
        RunupResult r;
        const double t_full = s.time([&] { r = simulate_runup(sc.params, def); }, 1.0);
        add(t, {"averaged", model, "equations",
                fmt::format("full (7), {} {:g}", ode_method_name(def.ode.method), def.ode.rel_tol), t_full,
                held_error(r.held_rotor_speed, r.held_roller_speed), error_of, reference,
                fmt::format("{} steps, {}", r.stats.steps, summarize_runup(sc.params, r).outcome)});
        RunupSummary sum;
        const double t_st = s.time([&] { sum = summarize_runup(sc.params, r0); });
        add(t, {"averaged", model, "equations", "stationary curve at the held nominal speed", t_st,
                held_error(sum.stationary_rotor_speed, sum.stationary_roller_speed), error_of, reference,
                fmt::format("branch {}, {}", sum.branch, sum.outcome)});
    }
}

}  // namespace tradeoffs
