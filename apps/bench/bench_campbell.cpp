// gyrokit-bench-campbell: the Campbell diagram and critical speeds of finite-element
// rotors the way the commands compute them by default (the modes in range, on the
// continuation), against the same modes from a full solve at every speed and
// against every mode (the former default), in one run: time, ratio to the
// every-mode path, and how far the continuation's eigenvalues lie from the full
// solve's in units of the sum of the two error bounds.
// Exit status: 0 success, 2 bad input, 1 anything else.
#include "bench_clock.hpp"
#include "bench_common.hpp"
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/solve/continuation.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/io/table.hpp>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <memory>

using namespace gyrokit;

namespace {

using bench::seconds_since;

struct Run {
    double campbell = 0, critical = 0;
    CampbellDiagram cd;
    std::vector<CriticalSpeed> cs;
};

Run run(const SolverFactory& solver, const std::vector<double>& speeds, const CampbellOptions& co,
        const std::vector<int>& harmonics, Workers jobs) {
    Run r;
    auto t0 = std::chrono::steady_clock::now();
    r.cd = campbell(solver, speeds, co);
    r.campbell = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    r.cs = critical_speeds(solver, r.cd, harmonics, jobs);
    r.critical = seconds_since(t0);
    return r;
}

// Largest |lambda_c - lambda_f| / (bound_c + bound_f) over the modes of the
// continuation at the grid speeds, each against the nearest full-solve mode.
double deviation_over_bounds(const SolverFactory& cont, const SolverFactory& full, const std::vector<double>& speeds,
                             double band) {
    const SpectrumSolver a = cont(), b = full();
    double worst = 0.0;
    for (double w : speeds) {
        const QuadraticSpectrum sa = a(w), sb = b(w);
        for (const Mode& m : sa.modes) {
            double best = INFINITY, allowed = 0.0;
            for (const Mode& o : sb.modes)
                if (within_band(o, 1.1 * band, sb.real_tol) && std::abs(o.lambda - m.lambda) < best)
                    best = std::abs(o.lambda - m.lambda), allowed = m.error_bound + o.error_bound;
            worst = std::max(worst, allowed > 0.0 ? best / allowed : (best > 0.0 ? INFINITY : 0.0));
        }
    }
    return worst;
}

std::string speeds_of(const std::vector<CriticalSpeed>& cs) {
    std::string s;
    for (const auto& c : cs) s += (s.empty() ? "" : " ") + fmt::format("{:.6g}", c.speed);
    return s.empty() ? "-" : s;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Times the Campbell diagram and critical speeds of FE rotors: the modes in range on the "
                 "continuation (default) against full solves and against every mode"};
    std::vector<std::string> scenes = {"three_disk_rotor.toml", "three_disk_rotor_journal.toml", "compressor.toml",
                                       "fe_rotor.toml"};
    int jobs = 1;
    std::string format = "table";
    app.add_option("--scenes", scenes, "scene files under data/ (or paths)")->capture_default_str();
    app.add_option("--jobs", jobs, "threads for the speeds (1: the work of one core)")
        ->check(CLI::Range(1, 1024))
        ->capture_default_str();
    app.add_option("--format", format, "output format: table, csv or json")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    return bench::guarded_main([&] {
        const TableFormat fmt_out = parse_table_format(format);
        Table t({"case", "dofs", "speeds", "path", "campbell_s", "critical_s", "time_vs_every_mode", "branches",
                 "inserted", "ambiguous", "max_backward_error", "dev_over_bounds", "anchors", "critical_speeds_rad_s"});
        t.key = "campbell_benchmark";
        t.title = fmt::format("Campbell diagram and critical speeds ({} thread{})", jobs, jobs > 1 ? "s" : "");
        for (const std::string& name : scenes) {
            const std::string path = name.find('/') == std::string::npos ? std::string(GYROKIT_DATA_DIR) + "/" + name : name;
            const Scene sc = load_scene(path);
            if (!sc.speeds) throw InputError(path + ": no [speeds]");
            const std::vector<double> speeds = sc.speed_points();
            SolverOptions so;
            so.kind = SolverKind::Dense;
            const SolverChoice plan = choose_solver(sc.system, so);
            const CampbellOptions in_range = tracking_options(plan, kModesInRange, speeds, sc.analysis.harmonics, jobs);
            CampbellOptions every = tracking_options(plan, 0, speeds, sc.analysis.harmonics, jobs);
            const auto model = std::make_shared<const GyroscopicSystem>(sc.system);
            ContinuationOptions copt;
            copt.band = in_range.band;
            copt.workers = jobs;
            ContinuationReport rep;
            const auto t0 = std::chrono::steady_clock::now();
            const SolverFactory cont = continuation_solver(model, speeds, copt, &rep);
            const double setup = seconds_since(t0);

            const Run base = run(plan.make, speeds, every, sc.analysis.harmonics, jobs);
            const Run full = run(plan.make, speeds, in_range, sc.analysis.harmonics, jobs);
            Run fast = run(cont, speeds, in_range, sc.analysis.harmonics, jobs);
            fast.campbell += setup;   // the anchor's full solve and the checks belong to the diagram's cost
            const double dev = deviation_over_bounds(cont, plan.make, speeds, in_range.band);
            const double total_base = base.campbell + base.critical;
            const auto row = [&](const std::string& label, const Run& r, double d, const std::string& basis) {
                t.add_row({name, static_cast<long long>(sc.dofs()), static_cast<long long>(speeds.size()), label,
                           r.campbell, r.critical, (r.campbell + r.critical) / total_base,
                           static_cast<long long>(r.cd.branches.size()), static_cast<long long>(r.cd.inserted_speeds),
                           static_cast<long long>(r.cd.ambiguous_steps), r.cd.max_backward_error, d, basis,
                           speeds_of(r.cs)});
            };
            row("every mode, full solves", base, 0.0, "-");
            row("in range, full solves", full, 0.0, "-");
            // The projected pencil serves only with the steps along the branches off: no basis here.
            row("in range, continuation", fast, dev,
                fmt::format("{} full, {} checks", rep.anchors.size(), rep.checks.size()));
        }
        write_table(std::cout, t, fmt_out);
    });
}
