// sommerfeld: stationary speed curves of the motor-driven rotor / auto-balancer
// with their branches, stability, limit speed estimates and exact folds; or
// (--runup) a run-up through the full equations of motion with a summary.
#include <gyrokit/reports/sommerfeld_reports.hpp>
#include <gyrokit/study/sommerfeld_study.hpp>
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

SommerfeldRequest request_of(const Options& o) {
    SommerfeldRequest r;
    r.runup = o.runup;
    if (!o.speeds.empty()) r.speeds = SpeedRange::parse(o.speeds, "--speeds");
    if (!o.method.empty()) r.integrator = o.method;
    if (o.abs_opt->count()) r.abs_tol = o.abs_tol;
    if (o.rel_opt->count()) r.rel_tol = o.rel_tol;
    if (o.max_opt->count()) r.max_speed = o.max_speed;
    return r;
}

void run(const Options& o, const BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    SommerfeldStudy st = sommerfeld_study(sc, request_of(o), o.runup ? fraction_bar("run-up") : nullptr);
    if (o.runup) {
        write_result(out, st.tables, fmt, o.table);
        if (!o.plot.empty()) plot_if(o.plot, runup_figure(sc.params, *st.runup, sc.title));
        return;
    }
    // The first screen (table format): the summary and the folds; the rows on request.
    if (fmt == TableFormat::Text && !o.rows && o.table.empty()) {
        Table sum = st.tables[2];
        sum.title = fmt::format("Sommerfeld effect: summary (the {} stationary states: --rows, or --format csv|json)",
                                st.tables[0].rows());
        write_result(out, {sum, st.tables[1]}, fmt, "");
    } else {
        write_result(out, st.tables, fmt, o.table);
    }
    if (!o.plot.empty()) plot_if(o.plot, stationary_figure(st.analysis, st.speeds, sc.title));
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
        if (o->runup && o->rows) throw InputError("--rows prints the stationary states; not with --runup");
        const BalancerScene sc = load_balancer_scene(o->scene);
        sommerfeld_plan(sc, request_of(*o));   // checked before any file is claimed
        run(*o, sc, fmt, out);
    }}};
}

}  // namespace gyrokit::cli
