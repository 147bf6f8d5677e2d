// Auto-balancer benchmark: ODE method and tolerance vs final-phase error and
// time, and the averaged slow-phase equations vs the full equations of motion,
// on the scenes of Bilder 9 (compensating state) and 10 (damped offset).
#include "balancing/balancer_scene.hpp"
#include "balancing/simulation.hpp"
#include "balancing/synchronous_states.hpp"
#include "core/error.hpp"
#include "io/table.hpp"

#include <cmath>
#include <iostream>
#include <string>

using namespace gyrokit;

int main(int argc, char** argv) {
    const std::string fmt = argc > 1 ? argv[1] : "table";
    const double kPi = 3.14159265358979323846;
    Table t({"scene", "equations", "method", "tol", "steps", "seconds", "alpha1_deg", "alpha2_deg", "phase_error_deg"});
    t.title = "Auto-balancer: final-phase error vs reference (full equations, rk8pd, tol 1e-13)";
    for (const std::string name : {"bild9", "bild10"}) {
        const BalancerScene sc = load_balancer_scene(std::string(GYROKIT_DATA_DIR) + "/balancer_" + name + ".toml");
        SimulationSettings ref = sc.simulation;
        ref.ode.abs_tol = ref.ode.rel_tol = 1e-13;
        const SimulationResult r0 = simulate(sc.params, ref);
        auto row = [&](const std::string& eq, OdeMethod m, double tol) {
            SimulationSettings s = sc.simulation;
            s.ode.method = m;
            s.ode.abs_tol = s.ode.rel_tol = tol;
            SimulationResult r;
            try {
                r = eq == "full" ? simulate(sc.params, s) : simulate_averaged(sc.params, s);
            } catch (const Error& e) {
                std::cerr << name << " " << ode_method_name(m) << " " << tol << ": " << e.what() << "\n";
                return;
            }
            double err = 0.0;
            for (std::size_t i = 0; i < 2; ++i) err = std::max(err, phase_distance(r.final_alpha[i], r0.final_alpha[i]));
            t.add_row({name, eq, ode_method_name(m), tol, static_cast<long long>(r.stats.steps), r.stats.seconds,
                       r.final_alpha[0] * 180 / kPi, r.final_alpha[1] * 180 / kPi, err * 180 / kPi});
        };
        for (OdeMethod m : {OdeMethod::Rk8pd, OdeMethod::Rkf45, OdeMethod::Rkck, OdeMethod::Msadams})
            for (double tol : {1e-6, 1e-8, 1e-10, 1e-12}) row("full", m, tol);
        row("full", OdeMethod::Msbdf, 1e-8);
        for (double tol : {1e-6, 1e-10}) row("averaged", OdeMethod::Rk8pd, tol);
    }
    write_table(std::cout, t, parse_table_format(fmt));
}
