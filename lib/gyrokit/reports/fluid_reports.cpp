#include <gyrokit/reports/fluid_reports.hpp>

#include <fmt/format.h>

#include <cmath>
#include <vector>

namespace gyrokit {

namespace {

const LiquidModel kModels[] = {LiquidModel::MovingUndamped, LiquidModel::MovingDamped, LiquidModel::Rigid};

void add_speed_rows(Table& t, const FluidCriticalSpeeds& cs, const SpeedUnit& u, const std::vector<Cell>& front) {
    for (LiquidModel m : kModels) {
        long long i = 1;
        for (double w : cs.of(m)) {
            std::vector<Cell> row = front;
            row.insert(row.end(), {to_string(m), i++, u.factor * w});
            t.add_row(row);
        }
    }
}

}  // namespace

Table fluid_critical_table(const FluidCriticalSpeeds& cs, const SpeedUnit& u) {
    Table t({"model", "index", u.column("speed")});
    t.key = "critical_speeds";
    t.title = fmt::format("critical speeds ({})", u.name);
    add_speed_rows(t, cs, u, {});
    return t;
}

Table sloshing_modes_table(const FluidRotor& f, const FluidCriticalSpeeds& cs, const SpeedUnit& u) {
    const double w = !cs.moving_undamped.empty() ? cs.moving_undamped.front() : std::sqrt(f.k.gamma / f.m);
    Table t({"n", "sigma_over_omega", "lambda_kg_m", "mu_kg", "tau_1_s"});
    t.key = "sloshing_modes";
    t.title = fmt::format("sloshing modes (tau at w = {:.6g} {})", u.factor * w, u.name);
    for (const auto& m : f.liquid.modes)
        t.add_row({static_cast<long long>(m.n), m.sigma_over_omega(), m.lambda, m.mu, m.tau(w)});
    return t;
}

Table liquid_table(const FluidRotor& f, const FluidCriticalSpeeds& cs) {
    Table t({"quantity", "value", "unit"});
    t.key = "liquid";
    t.title = "liquid and rotor";
    const auto& L = f.liquid;
    t.add_row({std::string("m_star"), L.m_star, std::string("kg")});
    t.add_row({std::string("I_star"), L.I_star, std::string("kg m^2")});
    t.add_row({std::string("J_star"), L.J_star, std::string("kg m^2")});
    t.add_row({std::string("J_rigid"), L.J_rigid, std::string("kg m^2")});
    t.add_row({std::string("J_eq"), cs.J_eq, std::string("kg m^2")});
    t.add_row({std::string("J_eq_rigid"), cs.J_eq_rigid, std::string("kg m^2")});
    t.add_row({std::string("gamma"), f.k.gamma, std::string("N/m")});
    t.add_row({std::string("delta"), f.k.delta, std::string("N")});
    t.add_row({std::string("sloshing_modes"), static_cast<long long>(L.modes.size()), std::string("")});
    t.add_row({std::string("jstar_terms"), static_cast<long long>(L.jstar_terms), std::string("")});
    return t;
}

Table fill_sweep_table(const FillSweep& s, const SpeedUnit& u) {
    Table t({"fill_m", "model", "index", u.column("speed")});
    t.key = "critical_speeds_vs_fill";
    t.title = fmt::format("critical speeds ({}) against the free-surface radius R0 (m)", u.name);
    for (std::size_t k = 0; k < s.fills.size(); ++k) add_speed_rows(t, s.speeds[k], u, {s.fills[k]});
    return t;
}

Figure fill_sweep_figure(const FillSweep& s, const SpeedUnit& u, const std::string& title) {
    const char* colors[3] = {"#1f77b4", "#d62728", "#2ca02c"};
    Panel pan;
    pan.xlabel = "free-surface radius R0 (m)";
    pan.ylabel = "critical speed (" + u.name + ")";
    pan.title = title;
    for (int i = 0; i < 3; ++i) {
        Series se;
        se.label = to_string(kModels[i]);
        se.style = "points";
        se.color = colors[i];
        for (std::size_t k = 0; k < s.fills.size(); ++k)
            for (double w : s.speeds[k].of(kModels[i])) {
                se.x.push_back(s.fills[k]);
                se.y.push_back(u.factor * w);
            }
        pan.series.push_back(se);
    }
    Figure fig;
    fig.panels.push_back(pan);
    fig.title = "critical speeds against fill level";
    return fig;
}

}  // namespace gyrokit
