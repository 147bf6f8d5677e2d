// balancer: synchronous states of the two-roller auto-balancer and their
// stability per speed range, or (--simulate) a run of the equations of motion.
#include <gyrokit/balancing/balancer_scene.hpp>
#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

constexpr double kPi = 3.14159265358979323846;
double deg(double rad) { return rad * 180.0 / kPi; }

struct Options {
    std::string scene, format = "table", plot, method, table;
    double speed = 0.0, duration = 0.0, abs_tol = 0.0, rel_tol = 0.0;
    // Which of them were given on the command line.
    CLI::Option *speed_opt = nullptr, *duration_opt = nullptr, *abs_opt = nullptr, *rel_opt = nullptr;
    bool simulate = false, averaged = false, history = false, rows = false;
};

std::string alpha_col(std::size_t i) { return "alpha" + std::to_string(i + 1) + "_deg"; }

Table state_table(const AutobalancerParameters& p) {
    std::vector<std::string> cols{"state"};
    for (std::size_t i = 0; i < p.rollers.size(); ++i) cols.push_back(alpha_col(i));
    for (const char* c : {"range", "from_rad_s", "to_rad_s", "stable", "stable_eigen", "max_re_lambda_1_s", "compensating"})
        cols.push_back(c);
    Table t(cols);
    t.key = "synchronous_states";
    t.title = "Synchronous states and their stability (undamped slow equations; speeds in rad/s)";
    for (const auto& e : stability_table(p)) {
        std::vector<Cell> row{e.state.label};
        for (double a : e.state.alpha) row.push_back(deg(a));
        row.push_back(e.range.name);
        row.push_back(e.range.from);
        // The top range is unbounded; print it as text, never as a non-finite number.
        if (std::isfinite(e.range.to)) row.push_back(e.range.to); else row.push_back(std::string("inf"));
        row.push_back(e.stable_criterion);
        row.push_back(e.stable_eigen);
        row.push_back(e.max_real_eigenvalue);
        row.push_back(e.state.compensating);
        t.add_row(row);
    }
    return t;
}

std::string labels(const std::vector<std::string>& l) {
    std::string t;
    for (const auto& x : l) t += (t.empty() ? "" : ", ") + x;
    return t.empty() ? std::string("none") : t;
}

Table range_table(const AutobalancerParameters& p) {
    Table t({"range", "from_rad_s", "to_rad_s", "balances", "stable_compensating", "stable_other", "disputed"});
    t.key = "balancing_ranges";
    t.title = "Where the auto-balancer balances: stable synchronous states per speed range, speeds in rad/s";
    for (const auto& v : range_verdicts(stability_table(p))) {
        std::vector<Cell> row{v.range.name, v.range.from};
        if (std::isfinite(v.range.to)) row.push_back(v.range.to); else row.push_back(std::string("inf"));
        row.push_back(!v.compensating.empty());
        for (const auto* l : {&v.compensating, &v.other, &v.disputed}) row.push_back(labels(*l));
        t.add_row(row);
    }
    return t;
}

void run_states(const Options& o, const BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    const Table states = state_table(sc.params);
    Table ranges = range_table(sc.params);
    // The first screen (table format): the ranges; every state and range on request.
    if (fmt == TableFormat::Text && !o.rows && o.table.empty()) {
        ranges.title += fmt::format("; the {} state-range rows: --rows, or --format csv|json", states.rows());
        write_result(out, {ranges}, fmt, "");
    } else {
        write_result(out, {states, ranges}, fmt, o.table);
    }
}

// The stable state of the damped slow model nearest to the simulated phases.
struct Prediction {
    std::string label;
    std::vector<double> alpha;
    double distance = 1e300;
};

Prediction predict(const AutobalancerParameters& p, double Omega, const std::vector<double>& alpha) {
    Prediction best;
    if (p.rollers.empty() || !(p.m0 * p.eps0 > 0.0)) return best;
    for (const auto& s : synchronous_states(p)) {
        std::vector<double> a;
        try {
            a = damped_equilibrium(p, Omega, s.alpha);
        } catch (const SolverError&) {
            continue;
        }
        if (!stable_by_eigenvalues(slow_eigenvalues(p, Omega, a, true))) continue;
        double d = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, phase_distance(a[i], alpha[i]));
        if (d < best.distance) best = {s.label, a, d};
    }
    return best;
}

void run_simulation(const Options& o, BalancerScene& sc, TableFormat fmt, std::ostream& out) {
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
    s.ode.progress = fraction_bar("simulation");
    const SimulationResult r = o.averaged ? simulate_averaged(p, s) : simulate(p, s);

    std::vector<Table> tables;
    const std::size_t nr = p.rollers.size();
    if (o.history) {
        std::vector<std::string> cols{"t_s"};
        for (std::size_t i = 0; i < nr; ++i) cols.push_back(alpha_col(i));
        cols.push_back("speed_rad_s");
        cols.push_back("radius_m");
        Table h(cols);
        h.key = "history";
        h.title = "history";
        const std::size_t step = std::max<std::size_t>(1, r.t.size() / 200);
        for (std::size_t k = 0; k < r.t.size(); k += step) {
            std::vector<Cell> row{r.t[k]};
            for (std::size_t i = 0; i < nr; ++i) row.push_back(deg(wrap_phase(r.alpha[i][k])));
            row.push_back(r.speed[k]);
            row.push_back(r.radius[k]);
            h.add_row(row);
        }
        tables.push_back(h);
    }
    const Prediction pr = predict(p, r.final_speed, r.final_alpha);
    std::vector<std::string> cols{"equations", "method", "duration_s", "revolutions", "speed_rad_s", "residual_rms_m",
                                  "residual_max_m", "steps", "seconds", "predicted_state"};
    for (std::size_t i = 0; i < nr; ++i) cols.push_back("predicted_" + alpha_col(i));
    for (std::size_t i = 0; i < nr; ++i) cols.push_back(alpha_col(i));
    Table f(cols);
    f.key = "final_state";
    f.title = "final state (relative phases: means over the last revolutions)";
    std::vector<Cell> row{std::string(o.averaged ? "averaged" : "full"), ode_method_name(s.ode.method), s.duration,
                          r.revolutions, r.final_speed, r.residual_rms, r.residual_max,
                          static_cast<long long>(r.stats.steps), r.stats.seconds,
                          pr.label.empty() ? std::string("none") : pr.label};
    for (std::size_t i = 0; i < nr; ++i) {
        if (pr.label.empty()) row.push_back(std::string("")); else row.push_back(deg(pr.alpha[i]));
    }
    for (std::size_t i = 0; i < nr; ++i) row.push_back(deg(r.final_alpha[i]));
    f.add_row(row);
    tables.push_back(f);
    write_result(out, tables, fmt, o.table);

    if (!o.plot.empty()) {
        Figure fig;
        fig.title = sc.title.empty() ? "Auto-balancer simulation" : sc.title;
        Panel ph;
        ph.xlabel = "t (s)";
        ph.ylabel = "relative phase (deg)";
        for (std::size_t i = 0; i < nr; ++i) {
            Series se;
            se.label = "alpha" + std::to_string(i + 1);
            se.x = r.t;
            for (double a : r.alpha[i]) se.y.push_back(deg(a));
            ph.series.push_back(se);
        }
        fig.panels.push_back(ph);
        if (!o.averaged) {
            Panel rp;
            rp.xlabel = "t (s)";
            rp.ylabel = "rotor centre |r| (m)";
            rp.series.push_back({r.t, r.radius, "|r|", "lines", ""});
            fig.panels.push_back(rp);
        }
        plot_if(o.plot, fig);
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
    c->add_option("--plot", o->plot, "with --simulate: draw the phase histories into FILE.svg or FILE.png");
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
