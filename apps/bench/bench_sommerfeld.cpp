// Sommerfeld run-up benchmark: ODE method and tolerance vs time and accuracy of a
// run-up through the full equations of motion (7), on the rotor with unbalance
// (Bilder 3-6) and the rotor with unbalance and two rollers (Bilder 17-20), both
// passing the resonance. Accuracy against a reference run (rk8pd, tolerance 1e-12):
// the held rotor speed, and the time at which the rotor (no rollers) or the
// rollers pass half-way between omega_krit and the maximal nominal speed.
#include <gyrokit/balancing/sommerfeld.hpp>
#include "bench_common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/table.hpp>

#include <cmath>
#include <iostream>
#include <string>

using namespace gyrokit;
using namespace gyrokit::bench;

namespace {

double passage_time(const RunupResult& r, double level) {
    for (std::size_t k = 1; k < r.t.size(); ++k) {
        double v = r.rotor_speed[k], u = r.rotor_speed[k - 1];
        if (!r.roller_speed.empty()) {
            v = r.roller_speed[0][k];
            u = r.roller_speed[0][k - 1];
        }
        if (u < level && v >= level) return r.t[k - 1] + (r.t[k] - r.t[k - 1]) * (level - u) / (v - u);
    }
    return 0.0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string fmt = argc > 1 ? argv[1] : "table";
    Table t({"scene", "method", "tol", "steps", "seconds", "held_rotor_speed", "speed_error", "passage_s",
             "passage_error_s", "outcome"});
    t.title = "Sommerfeld run-up: error vs reference (rk8pd, tol 1e-12)";
    for (const std::string name : {"rotor", "two_rollers_unbalance"}) {
        const BalancerScene sc = load_data_balancer_scene("sommerfeld_" + name + ".toml");
        const double wk = sommerfeld_system(sc.params).omega_krit;
        const RunupSettings ref = sommerfeld_reference_settings(sc);
        const RunupResult r0 = simulate_runup(sc.params, ref);
        const double level = 0.5 * (wk + ref.max_speed), tp0 = passage_time(r0, level);
        auto row = [&](OdeMethod m, double tol) {
            RunupSettings s = ref;
            s.ode.method = m;
            s.ode.abs_tol = s.ode.rel_tol = tol;
            RunupResult r;
            try {
                r = simulate_runup(sc.params, s);
            } catch (const Error& e) {
                std::cerr << name << " " << ode_method_name(m) << " " << tol << ": " << e.what() << "\n";
                return;
            }
            const double tp = passage_time(r, level);
            t.add_row({name, ode_method_name(m), tol, static_cast<long long>(r.stats.steps), r.stats.seconds,
                       r.held_rotor_speed, std::fabs(r.held_rotor_speed - r0.held_rotor_speed), tp,
                       std::fabs(tp - tp0), summarize_runup(sc.params, r).outcome});
        };
        t.add_row({name, std::string("rk8pd (reference)"), 1e-12, static_cast<long long>(r0.stats.steps),
                   r0.stats.seconds, r0.held_rotor_speed, 0.0, tp0, 0.0, summarize_runup(sc.params, r0).outcome});
        for (OdeMethod m : {OdeMethod::Rk8pd, OdeMethod::Rkf45, OdeMethod::Rkck, OdeMethod::Msadams, OdeMethod::Msbdf})
            for (double tol : {1e-6, 1e-8, 1e-10}) row(m, tol);
    }
    write_table(std::cout, t, parse_table_format(fmt));
    return 0;
}
