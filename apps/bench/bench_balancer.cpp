// Auto-balancer benchmark: ODE method and tolerance vs final-phase error and
// time, and the averaged slow-phase equations vs the full equations of motion,
// on the scenes of Bilder 9 (compensating state) and 10 (damped offset).
#include "bench_common.hpp"
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/table.hpp>

#include <cmath>
#include <iostream>
#include <string>

using namespace gyrokit;
using namespace gyrokit::bench;

int main(int argc, char** argv) {
    const std::string fmt = argc > 1 ? argv[1] : "table";
    Table t({"scene", "equations", "method", "tol", "steps", "seconds", "alpha1_deg", "alpha2_deg", "phase_error_deg"});
    t.title = "Auto-balancer: final-phase error vs reference (full equations, rk8pd, tol 1e-13)";
    for (const std::string name : {"bild9", "bild10"}) {
        const BalancerScene sc = load_data_balancer_scene("balancer_" + name + ".toml");
        const SimulationResult r0 = balancer_reference(sc);
        auto row = [&](const std::string& eq, OdeMethod m, double tol) {
            SimulationResult r;
            try {
                r = run_balancer(sc, eq == "averaged", m, tol);
            } catch (const Error& e) {
                std::cerr << name << " " << ode_method_name(m) << " " << tol << ": " << e.what() << "\n";
                return;
            }
            t.add_row({name, eq, ode_method_name(m), tol, static_cast<long long>(r.stats.steps), r.stats.seconds,
                       r.final_alpha[0] * 180 / kPi, r.final_alpha[1] * 180 / kPi,
                       final_phase_error(r, r0) * 180 / kPi});
        };
        for (OdeMethod m : {OdeMethod::Rk8pd, OdeMethod::Rkf45, OdeMethod::Rkck, OdeMethod::Msadams})
            for (double tol : {1e-6, 1e-8, 1e-10, 1e-12}) row("full", m, tol);
        row("full", OdeMethod::Msbdf, 1e-8);
        for (double tol : {1e-6, 1e-10}) row("averaged", OdeMethod::Rk8pd, tol);
    }
    write_table(std::cout, t, parse_table_format(fmt));
}
