// balancer: synchronous states of the two-roller auto-balancer and their
// stability per speed range, or (--simulate) a run of the equations of motion.
#include <gyrokit/balancing/balancer_scene.hpp>
#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/reports/balancer_reports.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    std::string scene, format = "table", plot, method, table;
    double speed = 0.0, duration = 0.0, abs_tol = 0.0, rel_tol = 0.0;
    // Which of them were given on the command line.
    CLI::Option *speed_opt = nullptr, *duration_opt = nullptr, *abs_opt = nullptr, *rel_opt = nullptr;
    bool simulate = false, averaged = false, history = false, rows = false;
};

void run_states(const Options& o, const BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    const std::vector<StateStability> stability = stability_table(sc.params);
    const Table states = synchronous_states_table(sc.params, stability);
    Table ranges = balancing_ranges_table(range_verdicts(stability));
    // The first screen (table format): the ranges; every state and range on request.
    if (fmt == TableFormat::Text && !o.rows && o.table.empty()) {
        ranges.title += fmt::format("; the {} state-range rows: --rows, or --format csv|json", states.rows());
        write_result(out, {ranges}, fmt, "");
    } else {
        write_result(out, {states, ranges}, fmt, o.table);
    }
}

// The scene's [simulation] with the command line's overrides, checked.
SimulationSettings simulation_settings(const Options& o, BalancerScene& sc) {
    AutobalancerParameters& p = sc.params;
    if (o.speed_opt->count()) {
        if (!(o.speed > 0.0) || !std::isfinite(o.speed))
            throw InputError(fmt::format("--speed {}: allowed: a finite number > 0 (rad/s)", o.speed));
        p.drive = Drive::PrescribedSpeed;
        p.speed = o.speed;
    }
    if (!sc.has_simulation)
        throw InputError(sc.file + ": --simulate needs a [simulation] table (duration, alpha1, alpha2)");
    // Without bearing damping the free vibration never decays and no state is stationary.
    if (!(p.c_x > 0.0) || !(p.c_y > 0.0))
        throw InputError(fmt::format("{}: [model] c_x = {}, c_y = {}: the simulation needs bearing damping c_x, c_y > 0 "
                                     "N s/m", sc.file, p.c_x, p.c_y));
    SimulationSettings s = sc.simulation;
    if (o.duration_opt->count()) {
        if (!(o.duration > 0.0) || !std::isfinite(o.duration))
            throw InputError(fmt::format("--duration {}: allowed: a finite number > 0 (s)", o.duration));
        s.duration = o.duration;
    }
    if (!o.method.empty()) s.ode.method = parse_ode_method(o.method);
    if (o.abs_opt->count()) s.ode.abs_tol = o.abs_tol;
    if (o.rel_opt->count()) s.ode.rel_tol = o.rel_tol;
    if (!(s.ode.abs_tol > 0.0) || !(s.ode.rel_tol > 0.0) || !(s.ode.abs_tol < 1.0) || !(s.ode.rel_tol < 1.0))
        throw InputError(fmt::format("--abs-tol {} / --rel-tol {}: allowed: 0 < tolerance < 1", s.ode.abs_tol,
                                     s.ode.rel_tol));
    if (o.averaged && p.drive != Drive::PrescribedSpeed)
        throw InputError("--averaged: the slow-phase equations need a prescribed speed (give --speed)");
    return s;
}

void run_simulation(const Options& o, BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    SimulationSettings s = simulation_settings(o, sc);
    s.ode.progress = fraction_bar("simulation");
    const AutobalancerParameters& p = sc.params;
    const SimulationResult r = o.averaged ? simulate_averaged(p, s) : simulate(p, s);
    std::vector<Table> tables;
    if (o.history) tables.push_back(simulation_history_table(r));
    tables.push_back(simulation_final_table(s, r, o.averaged, nearest_stable_state(p, r.final_speed, r.final_alpha)));
    write_result(out, tables, fmt, o.table);
    if (!o.plot.empty()) plot_if(o.plot, simulation_figure(r, o.averaged, sc.title));
}

}  // namespace

std::vector<Command> add_balancer_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* c = app.add_subcommand("balancer", "two-roller auto-balancer: synchronous states and their stability, "
                                             "or --simulate the equations of motion");
    c->add_option("scene", o->scene, "scene file (TOML, [model] type = \"autobalancer\")")->required();
    c->add_option("--format", o->format, "output format: table, csv or json")->capture_default_str();
    c->add_flag("--simulate", o->simulate, "integrate the equations of motion (18) with the scene's [simulation]");
    c->add_flag("--averaged", o->averaged, "with --simulate: integrate the averaged slow-phase equations instead");
    c->add_flag("--history", o->history, "with --simulate: also print the phase histories (about 200 rows)");
    o->speed_opt = c->add_option("--speed", o->speed, "with --simulate: prescribed rotor speed in rad/s (overrides the scene)");
    o->duration_opt = c->add_option("--duration", o->duration, "with --simulate: simulated time in s (overrides the scene)");
    c->add_flag("--rows", o->rows, "table format: every state and range too, not only the ranges' verdicts");
    c->add_option("--table", o->table, "only this table: synchronous_states or balancing_ranges (--simulate: final_state "
                                       "or history with --history); CSV holds the first unless one is named");
    c->add_option("--integrator", o->method, "with --simulate: ODE method (rk8pd, rkf45, rkck, rk4, rk2, msadams, "
                                         "rk4imp, bsimp, msbdf)");
    o->abs_opt = c->add_option("--abs-tol", o->abs_tol, "with --simulate: absolute tolerance");
    o->rel_opt = c->add_option("--rel-tol", o->rel_tol, "with --simulate: relative tolerance");
    add_output_option(c, "--plot", o->plot, "with --simulate: draw the phase histories into FILE.svg or FILE.png");
    return {{c, [o](std::ostream& out) {
        const TableFormat fmt = parse_table_format(o->format);
        check_plot_path(o->plot);
        if (!o->simulate && (o->averaged || o->history || o->speed_opt->count() || o->duration_opt->count() ||
                             !o->method.empty() || o->abs_opt->count() || o->rel_opt->count() || !o->plot.empty()))
            throw InputError("--averaged, --history, --speed, --duration, --integrator, --abs-tol, --rel-tol and --plot "
                             "need --simulate");
        if (o->simulate && o->rows) throw InputError("--rows prints the synchronous states; not with --simulate");
        BalancerScene sc = load_balancer_scene(o->scene);
        if (o->simulate)
            run_simulation(*o, sc, fmt, out);
        else
            run_states(*o, sc, fmt, out);
    }}};
}

}  // namespace gyrokit::cli
