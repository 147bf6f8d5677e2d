// sommerfeld: stationary speed curves of the motor-driven rotor / auto-balancer
// with their branches, stability, limit speed estimates and exact folds; or
// (--runup) a run-up through the full equations of motion with a summary.
#include <gyrokit/balancing/balancer_scene.hpp>
#include <gyrokit/balancing/runup.hpp>
#include <gyrokit/balancing/sommerfeld.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/speed_range.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <memory>

namespace gyrokit::cli {

namespace {

constexpr double kPi = 3.14159265358979323846;
double deg(double rad) { return rad * 180.0 / kPi; }

struct Options {
    std::string scene, format = "table", plot, method, speeds, table;
    double abs_tol = 0.0, rel_tol = 0.0, max_speed = 0.0;
    CLI::Option *abs_opt = nullptr, *rel_opt = nullptr, *max_opt = nullptr;
    bool runup = false, rows = false;
};

Table summary_table() {
    Table t({"quantity", "value", "unit"});
    t.key = "summary";
    t.title = "summary";
    return t;
}

void add(Table& t, const std::string& q, Cell v, const std::string& unit = "") { t.add_row({q, std::move(v), unit}); }

// Splits a sampled curve into runs of equal stability, so that unstable parts can be drawn dashed.
void add_curve(Panel& panel, const std::vector<StationaryPoint>& c, bool roller, const std::string& label) {
    std::size_t i = 0;
    bool first_stable = true, first_unstable = true;
    while (i < c.size()) {
        std::size_t j = i;
        Series s;
        s.style = c[i].stable ? "lines" : "dashed";
        s.color = roller ? "#d62728" : "#1f77b4";
        bool& first = c[i].stable ? first_stable : first_unstable;
        s.label = first ? label + (c[i].stable ? " (stable)" : " (unstable)") : "";
        first = false;
        // Overlap by one point so that the segments join.
        for (; j < c.size() && c[j].stable == c[i].stable; ++j) {
            s.x.push_back(c[j].nominal);
            s.y.push_back(roller ? c[j].roller_speed : c[j].rotor_speed);
        }
        if (j < c.size()) {
            s.x.push_back(c[j].nominal);
            s.y.push_back(roller ? c[j].roller_speed : c[j].rotor_speed);
        }
        panel.series.push_back(s);
        i = j;
    }
}

// "branch rotor_speed (stable|unstable)" of each state, rad/s.
std::string states_text(const std::vector<StationaryPoint>& states) {
    std::string t;
    for (const auto& q : states)
        t += fmt::format("{}{} {:.6g} ({})", t.empty() ? "" : "; ", q.branch, q.rotor_speed,
                         q.stable ? "stable" : "unstable");
    return t.empty() ? std::string("none") : t;
}

// Where a slow run-up from rest ends: it follows the resonance branch up to its fold.
std::string runup_verdict(const SommerfeldAnalysis& a, double nominal) {
    if (!a.has_jump) return "no fold: the rotor speed follows the nominal speed continuously";
    if (nominal < a.jump_down.point.nominal)
        return fmt::format("below the resonance (nominal speed below jump_down {:.6g}: one state only)",
                           a.jump_down.point.nominal);
    if (nominal < a.jump_up.point.nominal)
        return fmt::format("captured below the resonance (nominal speed between jump_down {:.6g} and jump_up {:.6g})",
                           a.jump_down.point.nominal, a.jump_up.point.nominal);
    return fmt::format("passes the resonance: jumps up at nominal {:.6g}", a.jump_up.point.nominal);
}

void run_stationary(const Options& o, const BalancerScene& sc, TableFormat fmt, std::ostream& out) {
    const SommerfeldAnalysis a = analyse_sommerfeld(sc.params);
    const SommerfeldSystem& s = a.system;
    const double nominal = sc.params.L0 / sc.params.beta0;
    SpeedRange range;
    if (!o.speeds.empty()) {
        range = SpeedRange::parse(o.speeds, "--speeds");
        range.validate("--speeds");
    } else {
        range.from = 0.0;
        range.to = 1.25 * std::max(nominal, a.has_jump ? a.jump_up.point.nominal : a.estimate);
        range.count = 201;
    }
    std::vector<std::string> cols{"nominal_rad_s", "branch", "rotor_speed_rad_s"};
    if (s.n > 0) cols.push_back("roller_speed_rad_s");
    cols.push_back("stable");
    Table curves(cols);
    curves.key = "stationary_states";
    curves.title = "stationary states (Omega = L0 / beta0; rotor speed omega0, roller speed omega_e)";
    for (double W : range.points())
        for (const auto& q : stationary_states(a, W)) {
            std::vector<Cell> row{W, q.branch, q.rotor_speed};
            if (s.n > 0) row.push_back(q.roller_speed);
            row.push_back(q.stable);
            curves.add_row(row);
        }
    Table f({"fold", "nominal_rad_s", "rotor_speed_rad_s", "roller_speed_rad_s"});
    f.key = "folds";
    f.title = "folds of the stationary curve (local extrema of Omega)";
    for (const auto& x : a.folds)
        f.add_row({std::string(x.maximum ? "maximum" : "minimum"), x.point.nominal, x.point.rotor_speed,
                   x.point.roller_speed});

    Table sum = summary_table();
    add(sum, "rollers", static_cast<long long>(s.n));
    add(sum, "omega_krit", s.omega_krit, "rad/s");
    add(sum, "nominal_speed", nominal, "rad/s");
    add(sum, "limit_speed_estimate", a.estimate, "rad/s");
    add(sum, "estimate_equation", std::string(s.n == 0 ? "(17)" : s.n == 1 ? "(26)" : "(43) / (26) with factor 2"));
    if (a.has_jump) {
        add(sum, "jump_up", a.jump_up.point.nominal, "rad/s");
        add(sum, "jump_up_rotor_speed", a.jump_up.point.rotor_speed, "rad/s");
        if (s.n > 0) add(sum, "jump_up_roller_speed", a.jump_up.point.roller_speed, "rad/s");
        add(sum, "jump_down", a.jump_down.point.nominal, "rad/s");
        add(sum, "jump_down_rotor_speed", a.jump_down.point.rotor_speed, "rad/s");
        if (s.n > 0) add(sum, "jump_down_roller_speed", a.jump_down.point.roller_speed, "rad/s");
        add(sum, "estimate_below_jump_up_percent", 100.0 * (a.jump_up.point.nominal - a.estimate) / a.jump_up.point.nominal, "%");
    } else {
        add(sum, "jump_up", std::string("none"));
        add(sum, "jump_down", std::string("none"));
    }
    if (s.compensating) add(sum, "synchronous_speed_at_nominal", synchronous_point(s, nominal).rotor_speed, "rad/s");
    add(sum, "states_at_nominal", states_text(stationary_states(a, nominal)), "rad/s");
    add(sum, "quasi_static_runup", runup_verdict(a, nominal), "rad/s");
    // The first screen (table format): the summary and the folds; the rows on request.
    if (fmt == TableFormat::Text && !o.rows && o.table.empty()) {
        sum.title = fmt::format("Sommerfeld effect: summary (the {} stationary states: --rows, or --format csv|json)",
                                curves.rows());
        write_result(out, {sum, f}, fmt, "");
    } else {
        write_result(out, {curves, f, sum}, fmt, o.table);
    }

    if (!o.plot.empty()) {
        Figure fig;
        fig.title = sc.title.empty() ? "Stationary speeds (Sommerfeld effect)" : sc.title;
        const double p_max = range.to / (1.0 - s.n * s.beta_e / s.beta0);
        const std::vector<StationaryPoint> c = stationary_curve(a, std::max(p_max, 1e-6), 4000);
        std::vector<StationaryPoint> shown;
        for (const auto& q : c)
            if (q.nominal <= range.to) shown.push_back(q);
        Panel p;
        p.xlabel = "nominal speed Omega (rad/s)";
        p.ylabel = "speed (rad/s)";
        p.xmin = range.from;
        p.xmax = range.to;
        add_curve(p, shown, false, "rotor omega0");
        if (s.n > 0) add_curve(p, shown, true, "rollers omega_e");
        if (s.compensating) {
            Series sy{{range.from, range.to},
                      {synchronous_point(s, range.from).rotor_speed, synchronous_point(s, range.to).rotor_speed},
                      "synchronous (37)", "dashed", "#2ca02c"};
            p.series.push_back(sy);
        }
        Series est{{a.estimate, a.estimate}, {0.0, range.to}, "estimate", "dashed", "#7f7f7f"};
        p.series.push_back(est);
        fig.panels.push_back(p);
        plot_if(o.plot, fig);
    }
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
    const std::size_t nr = p.rollers.size();

    std::vector<std::string> cols{"t_s", "nominal_rad_s", "rotor_speed_rad_s"};
    for (std::size_t i = 0; i < nr; ++i) cols.push_back("roller" + std::to_string(i + 1) + "_speed_rad_s");
    for (const char* c : {"amplitude_m", "torque_rotor_Nm", "torque_rollers_Nm"}) cols.push_back(c);
    if (nr == 2) cols.push_back("phase_difference_deg");
    Table h(cols);
    h.key = "runup_history";
    h.title = "run-up history";
    const std::size_t step = std::max<std::size_t>(1, r.t.size() / 200);
    for (std::size_t k = 0; k < r.t.size(); k += step) {
        std::vector<Cell> row{r.t[k], r.nominal[k], r.rotor_speed[k]};
        for (std::size_t i = 0; i < nr; ++i) row.push_back(r.roller_speed[i][k]);
        row.push_back(r.amplitude[k]);
        row.push_back(r.torque_rotor[k]);
        row.push_back(r.torque_rollers[k]);
        if (nr == 2) row.push_back(deg(r.phase_difference[k]));
        h.add_row(row);
    }
    Table sum = summary_table();
    add(sum, "method", ode_method_name(s.ode.method));
    add(sum, "abs_tol", s.ode.abs_tol);
    add(sum, "rel_tol", s.ode.rel_tol);
    add(sum, "omega_krit", sm.omega_krit, "rad/s");
    if (sm.jump_up > 0.0) add(sum, "jump_up", sm.jump_up, "rad/s"); else add(sum, "jump_up", std::string("none"));
    add(sum, "max_speed", s.max_speed, "rad/s");
    add(sum, "held_rotor_speed", r.held_rotor_speed, "rad/s");
    if (nr > 0) add(sum, "held_roller_speed", r.held_roller_speed, "rad/s");
    add(sum, "stationary_branch", sm.branch);
    add(sum, "stationary_rotor_speed", sm.stationary_rotor_speed, "rad/s");
    if (nr > 0) add(sum, "stationary_roller_speed", sm.stationary_roller_speed, "rad/s");
    add(sum, "held_amplitude_m", r.held_amplitude, "m");
    if (nr == 2) add(sum, "held_phase_difference_deg", deg(r.held_phase_difference), "deg");
    for (std::size_t i = 0; i < nr; ++i) add(sum, "held_alpha" + std::to_string(i + 1) + "_deg", deg(r.held_alpha[i]), "deg");
    add(sum, "steps", static_cast<long long>(r.stats.steps));
    add(sum, "seconds", r.stats.seconds, "s");
    add(sum, "outcome", sm.outcome);
    add(sum, "captured", sm.captured);
    write_result(out, {h, sum}, fmt, o.table);

    if (!o.plot.empty()) {
        Figure fig;
        fig.title = sc.title.empty() ? "Run-up" : sc.title;
        Panel sp;
        sp.xlabel = "t (s)";
        sp.ylabel = "speed (rad/s)";
        sp.series.push_back({r.t, r.nominal, "nominal Omega", "dashed", "#7f7f7f"});
        sp.series.push_back({r.t, r.rotor_speed, "rotor", "lines", "#1f77b4"});
        for (std::size_t i = 0; i < nr; ++i)
            sp.series.push_back({r.t, r.roller_speed[i], "roller " + std::to_string(i + 1), "lines", i ? "#2ca02c" : "#d62728"});
        Panel ap;
        ap.xlabel = "t (s)";
        ap.ylabel = "vibration amplitude |r| (m)";
        ap.series.push_back({r.t, r.amplitude, "|r|", "lines", ""});
        Panel tp;
        tp.xlabel = "t (s)";
        tp.ylabel = "vibration torque (N m)";
        if (p.m0 * p.eps0 > 0.0) tp.series.push_back({r.t, r.torque_rotor, "rotor B0", "lines", "#1f77b4"});
        if (nr > 0) tp.series.push_back({r.t, r.torque_rollers, "rollers sum B_i", "lines", "#d62728"});
        fig.panels = {sp, ap, tp};
        plot_if(o.plot, fig);
    }
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
    c->add_option("--plot", o->plot, "draw the curves or the run-up into FILE.svg or FILE.png");
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
