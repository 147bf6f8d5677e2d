#include <gyrokit/reports/sommerfeld_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace gyrokit {

using detail::degrees;

namespace {

Table quantity_table() {
    Table t({"quantity", "value", "unit"});
    t.key = "summary";
    t.title = "summary";
    return t;
}

void add(Table& t, const std::string& q, Cell v, const std::string& unit = "") { t.add_row({q, std::move(v), unit}); }

// "branch rotor_speed (stable|unstable)" of each state, rad/s.
std::string states_text(const std::vector<StationaryPoint>& states) {
    std::string t;
    for (const auto& q : states)
        t += fmt::format("{}{} {:.6g} ({})", t.empty() ? "" : "; ", q.branch, q.rotor_speed,
                         q.stable ? "stable" : "unstable");
    return t.empty() ? std::string("none") : t;
}

// quasi_static_runup in words, with the fold speeds it is judged by.
std::string runup_text(const SommerfeldAnalysis& a, double nominal) {
    const double down = a.jump_down.point.nominal, up = a.jump_up.point.nominal;
    switch (quasi_static_runup(a, nominal)) {
        case QuasiStaticRunup::Continuous:
            return "no fold: the rotor speed follows the nominal speed continuously";
        case QuasiStaticRunup::BelowResonance:
            return fmt::format("below the resonance (nominal speed below jump_down {:.6g}: one state only)", down);
        case QuasiStaticRunup::Captured:
            return fmt::format("captured below the resonance (nominal speed between jump_down {:.6g} and jump_up "
                               "{:.6g})", down, up);
        case QuasiStaticRunup::Passes: break;
    }
    return fmt::format("passes the resonance: jumps up at nominal {:.6g}", up);
}

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

}  // namespace

SpeedRange stationary_speeds(const AutobalancerParameters& p, const SommerfeldAnalysis& a) {
    const double nominal = p.L0 / p.beta0;
    SpeedRange range;
    range.from = 0.0;
    range.to = 1.25 * std::max(nominal, a.has_jump ? a.jump_up.point.nominal : a.estimate);
    range.count = 201;
    return range;
}

Table stationary_states_table(const SommerfeldAnalysis& a, const SpeedRange& speeds) {
    const bool rollers = a.system.n > 0;
    std::vector<std::string> cols{"nominal_rad_s", "branch", "rotor_speed_rad_s"};
    if (rollers) cols.push_back("roller_speed_rad_s");
    cols.push_back("stable");
    Table t(cols);
    t.key = "stationary_states";
    t.title = "stationary states (Omega = L0 / beta0; rotor speed omega0, roller speed omega_e)";
    for (double W : speeds.points())
        for (const auto& q : stationary_states(a, W)) {
            std::vector<Cell> row{W, q.branch, q.rotor_speed};
            if (rollers) row.push_back(q.roller_speed);
            row.push_back(q.stable);
            t.add_row(row);
        }
    return t;
}

Table folds_table(const SommerfeldAnalysis& a) {
    Table t({"fold", "nominal_rad_s", "rotor_speed_rad_s", "roller_speed_rad_s"});
    t.key = "folds";
    t.title = "folds of the stationary curve (local extrema of Omega)";
    for (const auto& x : a.folds)
        t.add_row({std::string(x.maximum ? "maximum" : "minimum"), x.point.nominal, x.point.rotor_speed,
                   x.point.roller_speed});
    return t;
}

Table sommerfeld_summary_table(const AutobalancerParameters& p, const SommerfeldAnalysis& a) {
    const SommerfeldSystem& s = a.system;
    const double nominal = p.L0 / p.beta0;
    Table sum = quantity_table();
    add(sum, "rollers", static_cast<long long>(s.n));
    add(sum, "omega_krit", s.omega_krit, "rad/s");
    add(sum, "nominal_speed", nominal, "rad/s");
    add(sum, "limit_speed_estimate", a.estimate, "rad/s");
    add(sum, "estimate_equation", std::string(s.n == 0 ? "(17)" : s.n == 1 ? "(26)" : "(43) / (26) with factor 2"));
    if (a.has_jump) {
        const StationaryPoint &up = a.jump_up.point, &down = a.jump_down.point;
        add(sum, "jump_up", up.nominal, "rad/s");
        add(sum, "jump_up_rotor_speed", up.rotor_speed, "rad/s");
        if (s.n > 0) add(sum, "jump_up_roller_speed", up.roller_speed, "rad/s");
        add(sum, "jump_down", down.nominal, "rad/s");
        add(sum, "jump_down_rotor_speed", down.rotor_speed, "rad/s");
        if (s.n > 0) add(sum, "jump_down_roller_speed", down.roller_speed, "rad/s");
        add(sum, "estimate_below_jump_up_percent", 100.0 * (up.nominal - a.estimate) / up.nominal, "%");
    } else {
        add(sum, "jump_up", std::string("none"));
        add(sum, "jump_down", std::string("none"));
    }
    if (s.compensating) add(sum, "synchronous_speed_at_nominal", synchronous_point(s, nominal).rotor_speed, "rad/s");
    add(sum, "states_at_nominal", states_text(stationary_states(a, nominal)), "rad/s");
    add(sum, "quasi_static_runup", runup_text(a, nominal), "rad/s");
    return sum;
}

Figure stationary_figure(const SommerfeldAnalysis& a, const SpeedRange& speeds, const std::string& title) {
    const SommerfeldSystem& s = a.system;
    Figure fig;
    fig.title = title.empty() ? "Stationary speeds (Sommerfeld effect)" : title;
    // The hanging speed at which the curve leaves the range (Omega(p) >= p (1 - n beta_e / beta0)).
    const double p_max = speeds.to / (1.0 - s.n * s.beta_e / s.beta0);
    std::vector<StationaryPoint> shown;
    for (const auto& q : stationary_curve(a, std::max(p_max, 1e-6), 4000))
        if (q.nominal <= speeds.to) shown.push_back(q);
    Panel p;
    p.xlabel = "nominal speed Omega (rad/s)";
    p.ylabel = "speed (rad/s)";
    p.xmin = speeds.from;
    p.xmax = speeds.to;
    add_curve(p, shown, false, "rotor omega0");
    if (s.n > 0) add_curve(p, shown, true, "rollers omega_e");
    if (s.compensating) {
        const double from = synchronous_point(s, speeds.from).rotor_speed, to = synchronous_point(s, speeds.to).rotor_speed;
        p.series.push_back({{speeds.from, speeds.to}, {from, to}, "synchronous (37)", "dashed", "#2ca02c"});
    }
    p.series.push_back({{a.estimate, a.estimate}, {0.0, speeds.to}, "estimate", "dashed", "#7f7f7f"});
    fig.panels.push_back(p);
    return fig;
}

Table runup_history_table(const RunupResult& r) {
    const std::size_t nr = r.roller_speed.size();
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
        if (nr == 2) row.push_back(degrees(r.phase_difference[k]));
        h.add_row(row);
    }
    return h;
}

Table runup_summary_table(const RunupSettings& s, const RunupResult& r, const RunupSummary& sm) {
    const std::size_t nr = r.roller_speed.size();
    Table sum = quantity_table();
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
    if (nr == 2) add(sum, "held_phase_difference_deg", degrees(r.held_phase_difference), "deg");
    for (std::size_t i = 0; i < nr; ++i)
        add(sum, "held_alpha" + std::to_string(i + 1) + "_deg", degrees(r.held_alpha[i]), "deg");
    add(sum, "steps", static_cast<long long>(r.stats.steps));
    add(sum, "seconds", r.stats.seconds, "s");
    add(sum, "outcome", sm.outcome);
    add(sum, "captured", sm.captured);
    return sum;
}

Figure runup_figure(const AutobalancerParameters& p, const RunupResult& r, const std::string& title) {
    const std::size_t nr = r.roller_speed.size();
    Figure fig;
    fig.title = title.empty() ? "Run-up" : title;
    Panel sp;
    sp.xlabel = "t (s)";
    sp.ylabel = "speed (rad/s)";
    sp.series.push_back({r.t, r.nominal, "nominal Omega", "dashed", "#7f7f7f"});
    sp.series.push_back({r.t, r.rotor_speed, "rotor", "lines", "#1f77b4"});
    for (std::size_t i = 0; i < nr; ++i)
        sp.series.push_back(
            {r.t, r.roller_speed[i], "roller " + std::to_string(i + 1), "lines", i ? "#2ca02c" : "#d62728"});
    Panel ap;
    ap.xlabel = "t (s)";
    ap.ylabel = "vibration amplitude |r| (m)";
    ap.series.push_back({r.t, r.amplitude, "|r|", "lines", ""});
    Panel tp;
    tp.xlabel = "t (s)";
    tp.ylabel = "vibration torque (N m)";
    // Without an unbalance (or rollers) there is no torque of that kind to draw.
    if (p.m0 * p.eps0 > 0.0) tp.series.push_back({r.t, r.torque_rotor, "rotor B0", "lines", "#1f77b4"});
    if (nr > 0) tp.series.push_back({r.t, r.torque_rollers, "rollers sum B_i", "lines", "#d62728"});
    fig.panels = {sp, ap, tp};
    return fig;
}

}  // namespace gyrokit
