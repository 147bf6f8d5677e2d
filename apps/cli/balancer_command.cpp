// balancer: synchronous states of the two-roller auto-balancer and their
// stability per speed range, or (--simulate) a run of the equations of motion.
#include <gyrokit/reports/balancer_reports.hpp>
#include <gyrokit/study/balancer_study.hpp>
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

BalancerRequest request_of(const Options& o) {
    BalancerRequest r;
    r.simulate = o.simulate;
    r.averaged = o.averaged;
    if (o.speed_opt->count()) r.speed = o.speed;
    if (o.duration_opt->count()) r.duration = o.duration;
    if (!o.method.empty()) r.integrator = o.method;
    if (o.abs_opt->count()) r.abs_tol = o.abs_tol;
    if (o.rel_opt->count()) r.rel_tol = o.rel_tol;
    return r;
}

void run(const Options& o, const BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    const BalancerRequest rq = request_of(o);
    BalancerStudy st = balancer_study(sc, rq, o.simulate ? fraction_bar("simulation") : nullptr);
    if (o.simulate) {
        if (!o.history) st.tables.erase(st.tables.begin());   // the phase histories on request
        write_result(out, st.tables, fmt, o.table);
        if (!o.plot.empty()) plot_if(o.plot, simulation_figure(*st.simulation, o.averaged, sc.title));
        return;
    }
    // The first screen (table format): the ranges; every state and range on request.
    if (fmt == TableFormat::Text && !o.rows && o.table.empty()) {
        Table ranges = st.tables[1];
        ranges.title += fmt::format("; the {} state-range rows: --rows, or --format csv|json", st.tables[0].rows());
        write_result(out, {ranges}, fmt, "");
    } else {
        write_result(out, st.tables, fmt, o.table);
    }
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
        if (!o->simulate && (o->history || !o->plot.empty()))
            throw InputError("--history and --plot need --simulate");
        if (o->simulate && o->rows) throw InputError("--rows prints the synchronous states; not with --simulate");
        const BalancerScene sc = load_balancer_scene(o->scene);
        balancer_plan(sc, request_of(*o));   // checked before any file is claimed
        run(*o, sc, fmt, out);
    }}};
}

}  // namespace gyrokit::cli
