// Benchmark of the analyses on a model gyrokit did not build (the exported
// ROSS rotor, free axial and torsional DOFs, undamped; and the same with damped
// bearings): Campbell tracking against the bare eigensolves it needs at least,
// and the sparse solver's backward errors before and after verification.
// Prints two tables (docs/benchmarks.md).
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include "bench_common.hpp"
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/io/table.hpp>

#include <iostream>
#include <string>

using namespace gyrokit;
using namespace gyrokit::bench;

int main(int argc, char** argv) {
    return guarded_main([&] {
        const TableFormat fmt = argc > 1 ? parse_table_format(argv[1]) : TableFormat::Text;
        const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/ross_rotor_example/scene.toml");
        GyroscopicSystem damped = sc.system;
        Eigen::MatrixXd D = Eigen::MatrixXd::Zero(damped.size(), damped.size());
        for (int dof : {0, 1, 36, 37}) D(dof, dof) = 500.0;
        damped.damping.push_back({"bearings", to_sparse(D)});
        const std::vector<double> speeds = linspace(0.0, 1000.0, 101);

        Table t({"case", "speeds", "modes", "campbell_s", "bare_solves_s", "ratio", "inserted", "ambiguous",
                 "rigid_body", "stability_s", "unstable"});
        t.title = "Campbell diagram of the exported rotor (0-1000 rad/s, one thread) against 101 bare dense QZ solves";
        // Named, not a structured binding: lambdas below capture `sys` (clang 14 refuses bindings there).
        for (const auto& entry : {std::pair<std::string, const GyroscopicSystem*>{"ross undamped", &sc.system},
                                  {"ross damped bearings", &damped}}) {
            const std::string& name = entry.first;
            const GyroscopicSystem* sys = entry.second;
            for (int modes : {6, 0}) {
                CampbellOptions co;
                co.modes = modes;
                CampbellDiagram cd;
                const double tc = median_seconds([&] { cd = campbell(*sys, speeds, co); }, 1.0);
                const double tb = median_seconds([&] {
                    for (double w : speeds) solve_at_speed(*sys, w);
                }, 1.0);
                std::vector<StabilityChange> st;
                const double ts = median_seconds([&] { st = stability_changes(*sys, cd); }, 0.2);
                t.add_row({name, static_cast<long long>(speeds.size()), static_cast<long long>(cd.branches.size()), tc,
                           tb, tc / tb, static_cast<long long>(cd.inserted_speeds),
                           static_cast<long long>(cd.ambiguous_steps), static_cast<long long>(cd.rigid_body), ts,
                           static_cast<long long>(unstable_ranges(cd).size())});
            }
        }
        write_table(std::cout, t, fmt);
        std::cout << "\n";

        Table v({"case", "speed", "modes", "shift", "raw_max_backward_error", "refined_pairs",
                 "verified_max_backward_error", "max_rel_diff_to_qz", "seconds"});
        v.title = "sparse solver (target 0): backward errors before and after verification, against dense QZ";
        for (const auto& entry : {std::pair<std::string, const GyroscopicSystem*>{"ross undamped", &sc.system},
                                  {"ross damped bearings", &damped}}) {
            const std::string& name = entry.first;
            const GyroscopicSystem* sys = entry.second;
            for (double w : {0.0, 500.0, 1000.0}) {
                SparseEigenOptions o;
                o.modes = 10;
                const SparsePencil p = to_sparse(sys->at_speed(w));
                SparseSpectrum s;
                const double ts = median_seconds([&] { s = solve_quadratic_sparse(p, o, sys->whirl_pairs); }, 0.2);
                const QuadraticSpectrum d = solve_at_speed(*sys, w);
                double diff = 0.0, verified = 0.0;
                for (const Mode& m : s.modes) {
                    double nearest = 1e300;
                    for (const Mode& r : d.modes) nearest = std::min(nearest, std::abs(r.lambda - m.lambda) / std::abs(r.lambda));
                    diff = std::max(diff, nearest);
                    verified = std::max(verified, m.backward_error);
                }
                v.add_row({name, w, static_cast<long long>(s.modes.size()), s.shift.real(), s.max_raw_backward_error,
                           static_cast<long long>(s.refined), verified, diff, ts});
            }
        }
        write_table(std::cout, v, fmt);
    });
}
