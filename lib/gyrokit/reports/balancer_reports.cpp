#include <gyrokit/reports/balancer_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <algorithm>
#include <cmath>

namespace gyrokit {

using detail::degrees;

namespace {

std::string alpha_column(std::size_t i) { return "alpha" + std::to_string(i + 1) + "_deg"; }

// The top range is unbounded; print it as text, never as a non-finite number.
Cell range_end(double to) { return std::isfinite(to) ? Cell(to) : Cell(std::string("inf")); }

std::string labels(const std::vector<std::string>& l) {
    std::string t;
    for (const auto& x : l) t += (t.empty() ? "" : ", ") + x;
    return t.empty() ? std::string("none") : t;
}

}  // namespace

Table synchronous_states_table(const AutobalancerParameters& p, const std::vector<StateStability>& states) {
    std::vector<std::string> cols{"state"};
    for (std::size_t i = 0; i < p.rollers.size(); ++i) cols.push_back(alpha_column(i));
    for (const char* c :
         {"range", "from_rad_s", "to_rad_s", "stable", "stable_eigen", "max_re_lambda_1_s", "compensating"})
        cols.push_back(c);
    Table t(cols);
    t.key = "synchronous_states";
    t.title = "Synchronous states and their stability (undamped slow equations; speeds in rad/s)";
    for (const auto& e : states) {
        std::vector<Cell> row{e.state.label};
        for (double a : e.state.alpha) row.push_back(degrees(a));
        row.insert(row.end(), {e.range.name, e.range.from, range_end(e.range.to), e.stable_criterion, e.stable_eigen,
                               e.max_real_eigenvalue, e.state.compensating});
        t.add_row(row);
    }
    return t;
}

Table balancing_ranges_table(const std::vector<RangeVerdict>& verdicts) {
    Table t({"range", "from_rad_s", "to_rad_s", "balances", "stable_compensating", "stable_other", "disputed"});
    t.key = "balancing_ranges";
    t.title = "Where the auto-balancer balances: stable synchronous states per speed range, speeds in rad/s";
    for (const auto& v : verdicts)
        t.add_row({v.range.name, v.range.from, range_end(v.range.to), v.balances(), labels(v.compensating),
                   labels(v.other), labels(v.disputed)});
    return t;
}

Table simulation_history_table(const SimulationResult& r) {
    const std::size_t nr = r.alpha.size();
    std::vector<std::string> cols{"t_s"};
    for (std::size_t i = 0; i < nr; ++i) cols.push_back(alpha_column(i));
    cols.push_back("speed_rad_s");
    cols.push_back("radius_m");
    Table h(cols);
    h.key = "history";
    h.title = "history";
    const std::size_t step = std::max<std::size_t>(1, r.t.size() / 200);
    for (std::size_t k = 0; k < r.t.size(); k += step) {
        std::vector<Cell> row{r.t[k]};
        for (std::size_t i = 0; i < nr; ++i) row.push_back(degrees(wrap_phase(r.alpha[i][k])));
        row.push_back(r.speed[k]);
        row.push_back(r.radius[k]);
        h.add_row(row);
    }
    return h;
}

Table simulation_final_table(const SimulationSettings& s, const SimulationResult& r, bool averaged,
                             const NearestState& predicted) {
    const std::size_t nr = r.final_alpha.size();
    std::vector<std::string> cols{"equations", "method", "duration_s", "revolutions", "speed_rad_s", "residual_rms_m",
                                  "residual_max_m", "steps", "seconds", "predicted_state"};
    for (std::size_t i = 0; i < nr; ++i) cols.push_back("predicted_" + alpha_column(i));
    for (std::size_t i = 0; i < nr; ++i) cols.push_back(alpha_column(i));
    Table f(cols);
    f.key = "final_state";
    f.title = "final state (relative phases: means over the last revolutions)";
    const bool none = predicted.label.empty();
    std::vector<Cell> row{std::string(averaged ? "averaged" : "full"), ode_method_name(s.ode.method), s.duration,
                          r.revolutions, r.final_speed, r.residual_rms, r.residual_max,
                          static_cast<long long>(r.stats.steps), r.stats.seconds,
                          none ? std::string("none") : predicted.label};
    for (std::size_t i = 0; i < nr; ++i)
        row.push_back(none ? Cell(std::string("")) : Cell(degrees(predicted.alpha[i])));
    for (std::size_t i = 0; i < nr; ++i) row.push_back(degrees(r.final_alpha[i]));
    f.add_row(row);
    return f;
}

Figure simulation_figure(const SimulationResult& r, bool averaged, const std::string& title) {
    Figure fig;
    fig.title = title.empty() ? "Auto-balancer simulation" : title;
    Panel ph;
    ph.xlabel = "t (s)";
    ph.ylabel = "relative phase (deg)";
    for (std::size_t i = 0; i < r.alpha.size(); ++i) {
        Series se;
        se.label = "alpha" + std::to_string(i + 1);
        se.x = r.t;
        for (double a : r.alpha[i]) se.y.push_back(degrees(a));
        ph.series.push_back(se);
    }
    fig.panels.push_back(ph);
    // The averaged equations have no rotor centre motion to show.
    if (!averaged) {
        Panel rp;
        rp.xlabel = "t (s)";
        rp.ylabel = "rotor centre |r| (m)";
        rp.series.push_back({r.t, r.radius, "|r|", "lines", ""});
        fig.panels.push_back(rp);
    }
    return fig;
}

}  // namespace gyrokit
