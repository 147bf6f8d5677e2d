// fluid: critical speeds of a liquid-filled rotor (liquid moving, undamped and
// damped; liquid frozen as a solid), the sloshing coefficients, and with --fill a
// sweep of the free-surface radius R0 (the paper's Bild 2).
#include <gyrokit/analysis/fluid_critical_speeds.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

struct FluidOptions {
    Common common;
    std::string fill, table;
};

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

Table modes_table(const FluidRotor& f, double w, const SpeedUnit& u) {
    Table t({"n", "sigma_over_omega", "lambda_kg_m", "mu_kg", "tau_1_s"});
    t.key = "sloshing_modes";
    t.title = fmt::format("sloshing modes (tau at w = {:.6g} {})", u.factor * w, u.name);
    for (const auto& m : f.liquid.modes)
        t.add_row({static_cast<long long>(m.n), m.sigma_over_omega(), m.lambda, m.mu, m.tau(w)});
    return t;
}

std::vector<double> parse_fill(const std::string& text, double R) {
    const SpeedRange r = SpeedRange::parse(text, "--fill", 1.0);
    if (!(r.from > 0.0) || !(r.to < R))
        throw InputError(fmt::format("--fill '{}': R0 from {} to {}; allowed: 0 < R0 < R = {} (m)", text, r.from,
                                     r.to, R));
    return r.points();
}

}  // namespace

std::vector<Command> add_fluid_commands(CLI::App& app) {
    auto o = std::make_shared<FluidOptions>();
    std::vector<Command> cmds;
    auto* fl = app.add_subcommand("fluid", "liquid-filled rotor: critical speeds with moving and rigid liquid, "
                                           "sloshing coefficients, sweep over the fill level");
    add_common(fl, o->common, false);
    fl->add_option("--fill", o->fill, "sweep the free-surface radius R0 over FROM:TO:N (m)");
    fl->add_option("--table", o->table,
                   "only this table: critical_speeds, sloshing_modes or liquid (default: all; CSV holds the first)");
    fl->add_option("--plot", o->common.plot, "with --fill: critical speeds against R0 into FILE.svg or FILE.png");
    cmds.push_back({fl, [o](std::ostream& out) {
        if (!o->common.plot.empty() && o->fill.empty()) throw InputError("--plot: only together with --fill");
        const Context c = open_scene(o->common, false);
        if (!c.scene.fluid)
            throw InputError(fmt::format("{}: [model] type = '{}'; the fluid command needs type = \"fluid_rotor\"",
                                         c.scene.path, c.scene.model_type));
        const FluidRotorParameters p0 = *c.scene.fluid;
        if (!o->fill.empty()) {
            const std::vector<double> fills = parse_fill(o->fill, p0.R);
            Table t({"fill_m", "model", "index", c.unit.column("speed")});
            t.key = "critical_speeds_vs_fill";
            t.title = fmt::format("critical speeds ({}) against the free-surface radius R0 (m)", c.unit.name);
            Figure fig;
            Panel pan;
            pan.xlabel = "free-surface radius R0 (m)";
            pan.ylabel = "critical speed (" + c.unit.name + ")";
            pan.title = c.scene.title;
            Series s[3];
            const char* colors[3] = {"#1f77b4", "#d62728", "#2ca02c"};
            for (int i = 0; i < 3; ++i) {
                s[i].label = to_string(kModels[i]);
                s[i].style = "points";
                s[i].color = colors[i];
            }
            int skipped = 0;
            for (double R0 : fills) {
                FluidRotorParameters p = p0;
                p.R0 = R0;
                const FluidRotor f = build_fluid_rotor(p);
                FluidCriticalSpeeds cs;
                try {
                    cs = fluid_critical_speeds(f);
                } catch (const SolverError&) {
                    ++skipped;   // exactly at a sloshing resonance: no undamped answer
                    continue;
                }
                add_speed_rows(t, cs, c.unit, {R0});
                for (int i = 0; i < 3; ++i)
                    for (double w : cs.of(kModels[i])) {
                        s[i].x.push_back(R0);
                        s[i].y.push_back(c.unit.factor * w);
                    }
            }
            write_result(out, {t}, c.format, o->table);
            if (skipped) std::cerr << "note: " << skipped << " fill levels lie exactly at a sloshing resonance\n";
            for (auto& x : s) pan.series.push_back(x);
            fig.panels.push_back(pan);
            fig.title = "critical speeds against fill level";
            plot_if(o->common.plot, fig);
            return;
        }
        const FluidRotor f = build_fluid_rotor(p0);
        const FluidCriticalSpeeds cs = fluid_critical_speeds(f);
        Table crit({"model", "index", c.unit.column("speed")});
        crit.key = "critical_speeds";
        crit.title = fmt::format("critical speeds ({})", c.unit.name);
        add_speed_rows(crit, cs, c.unit, {});
        const double w1 = !cs.moving_undamped.empty() ? cs.moving_undamped.front() : std::sqrt(f.k.gamma / f.m);
        write_result(out, {crit, modes_table(f, w1, c.unit), liquid_table(f, cs)}, c.format, o->table);
    }});
    return cmds;
}

}  // namespace gyrokit::cli
