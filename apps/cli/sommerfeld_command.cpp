// sommerfeld: stationary speed curves of the motor-driven rotor / auto-balancer
// with their branches, stability, limit speed estimates and exact folds; or
// (--runup) a run-up through the full equations of motion with a summary.
#include <gyrokit/balancing/balancer_scene.hpp>
#include <gyrokit/balancing/runup.hpp>
#include <gyrokit/balancing/sommerfeld.hpp>
#include <gyrokit/reports/sommerfeld_reports.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/speed_range.hpp>

#include <cmath>
#include <fmt/format.h>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    std::string scene, format = "table", plot, method, speeds, table;
    double abs_tol = 0.0, rel_tol = 0.0, max_speed = 0.0;
    CLI::Option *abs_opt = nullptr, *rel_opt = nullptr, *max_opt = nullptr;
    bool runup = false, rows = false;
};

void run_stationary(const Options& o, const BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    const SommerfeldAnalysis a = analyse_sommerfeld(sc.params);
    // --speeds was checked before the scene was read.
    const SpeedRange range = o.speeds.empty() ? stationary_speeds(sc.params, a)
                                              : SpeedRange::parse(o.speeds, "--speeds");
    const Table curves = stationary_states_table(a, range), folds = folds_table(a);
    Table sum = sommerfeld_summary_table(sc.params, a);
    // The first screen (table format): the summary and the folds; the rows on request.
    if (fmt == TableFormat::Text && !o.rows && o.table.empty()) {
        sum.title = fmt::format("Sommerfeld effect: summary (the {} stationary states: --rows, or --format csv|json)",
                                curves.rows());
        write_result(out, {sum, folds}, fmt, "");
    } else {
        write_result(out, {curves, folds, sum}, fmt, o.table);
    }
    if (!o.plot.empty()) plot_if(o.plot, stationary_figure(a, range, sc.title));
}

void run_runup(const Options& o, const BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    if (!sc.has_runup)
        throw InputError(sc.file + ": --runup needs a [runup] table (max_speed, rise, hold, fall)");
    const AutobalancerParameters& p = sc.params;
    sommerfeld_system(p);   // the summary's analysis: reject unsuitable scenes before the run
    RunupSettings s = sc.runup;
    if (!o.method.empty()) s.ode.method = parse_ode_method(o.method);
    if (o.abs_opt->count()) s.ode.abs_tol = o.abs_tol;
    if (o.rel_opt->count()) s.ode.rel_tol = o.rel_tol;
    if (o.max_opt->count()) s.max_speed = o.max_speed;
    if (!(s.ode.abs_tol > 0.0 && s.ode.abs_tol < 1.0) || !(s.ode.rel_tol > 0.0 && s.ode.rel_tol < 1.0))
        throw InputError(fmt::format("--abs-tol {} / --rel-tol {}: allowed: 0 < tolerance < 1", s.ode.abs_tol,
                                     s.ode.rel_tol));
    if (!(s.max_speed > 0.0) || !std::isfinite(s.max_speed))
        throw InputError(fmt::format("--max-speed {}: allowed: a finite number > 0 (rad/s)", s.max_speed));
    s.ode.progress = fraction_bar("run-up");
    const RunupResult r = simulate_runup(p, s);
    const RunupSummary sm = summarize_runup(p, r);
    write_result(out, {runup_history_table(r), runup_summary_table(s, r, sm)}, fmt, o.table);
    if (!o.plot.empty()) plot_if(o.plot, runup_figure(p, r, sc.title));
}

}  // namespace

std::vector<Command> add_sommerfeld_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* c = app.add_subcommand("sommerfeld", "Sommerfeld effect of the motor-driven rotor and auto-balancer: "
                                               "stationary speed curves, limit speeds and folds, or --runup");
    c->add_option("scene", o->scene, "scene file (TOML, [model] type = \"autobalancer\" with L0, beta0)")->required();
    c->add_option("--format", o->format, "output format: table, csv or json")->capture_default_str();
    c->add_option("--speeds", o->speeds, "nominal speeds FROM:TO:N of the stationary curves, rad/s");
    c->add_flag("--runup", o->runup, "simulate the scene's [runup] through the full equations of motion (7)");
    c->add_flag("--rows", o->rows, "table format: every stationary state too, not only the summary and folds");
    c->add_option("--table", o->table, "only this table: stationary_states, folds, summary (--runup: runup_history, "
                                       "summary); CSV holds the first unless one is named");
    c->add_option("--integrator", o->method, "with --runup: ODE method (rk8pd, rkf45, rkck, rk4, rk2, msadams, rk4imp, "
                                         "bsimp, msbdf)");
    o->abs_opt = c->add_option("--abs-tol", o->abs_tol, "with --runup: absolute tolerance");
    o->rel_opt = c->add_option("--rel-tol", o->rel_tol, "with --runup: relative tolerance");
    o->max_opt = c->add_option("--max-speed", o->max_speed, "with --runup: maximal nominal speed, rad/s (overrides the scene)");
    add_output_option(c, "--plot", o->plot, "draw the curves or the run-up into FILE.svg or FILE.png");
    return {{c, [o](std::ostream& out) {
        const TableFormat fmt = parse_table_format(o->format);
        check_plot_path(o->plot);
        if (!o->runup && (!o->method.empty() || o->abs_opt->count() || o->rel_opt->count() || o->max_opt->count()))
            throw InputError("--integrator, --abs-tol, --rel-tol and --max-speed need --runup");
        if (o->runup && !o->speeds.empty()) throw InputError("--speeds sets the stationary curves; not with --runup");
        if (o->runup && o->rows) throw InputError("--rows prints the stationary states; not with --runup");
        if (!o->speeds.empty()) SpeedRange::parse(o->speeds, "--speeds").validate("--speeds");
        if (!o->method.empty()) parse_ode_method(o->method);
        const BalancerScene sc = load_balancer_scene(o->scene);
        if (o->runup)
            run_runup(*o, sc, fmt, out);
        else
            run_stationary(*o, sc, fmt, out);
    }}};
}

}  // namespace gyrokit::cli
